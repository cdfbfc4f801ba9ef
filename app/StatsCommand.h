#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw stats SOURCE (--sphere | --box | --labels)`: ROI statistics (max, mean, SD, SUVpeak,
// metabolic volume) in the volume's unit.
void addStatsCommand(CLI::App& app);

}  // namespace mvw::app
