#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw bench render STUDY`: ms per frame for each mode over an azimuth orbit, headless.
// Speed lives here and in tests/bench/, never in timed unit tests.
void addBenchCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
