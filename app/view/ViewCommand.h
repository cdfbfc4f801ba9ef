#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw view STUDY.json` or `mvw view --anatomical A [--functional F]`: the interactive window.
void addViewCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
