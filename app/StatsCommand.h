#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw stats SOURCE (--sphere | --box | --labels)`: ROI statistics (max, mean, SD, SUVpeak,
// metabolic volume) in the volume's unit.
void addStatsCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
