#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw view STUDY.json` or `mvw view --anatomical A [--functional F]`: the interactive window.
void addViewCommand(CLI::App& app);

}  // namespace mvw::app
