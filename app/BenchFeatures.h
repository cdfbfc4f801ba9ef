#pragma once
#include <CLI/CLI.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw bench features STUDY`: what each view's feature (glyphs, colour fusion, depth cue)
// costs over the same view without it, rendered interleaved over an azimuth orbit (see
// tests/bench/feature-cost).
void addBenchFeaturesCommand(CLI::App& bench, const pacs::Options& pacs);

}  // namespace mvw::app
