#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw phantom vessels|pet -o FILE ...`: synthetic volumes with known geometry (the vessel
// tree of the depth-cued MIP tests, the PET-like volume of the registration tests).
void addPhantomCommand(CLI::App& app);

}  // namespace mvw::app
