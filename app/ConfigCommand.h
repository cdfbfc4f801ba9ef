#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw config reference`: the study config's reference (every key, its type, values, default
// and description) as Markdown, made from the config's field tables; docs/config-reference.md
// is its output.
void addConfigCommand(CLI::App& app);

}  // namespace mvw::app
