#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw glyphmap -o FILE [--size N --count N --diameter D --seed S --voxel-mm MM]`: the paper's
// volumetric normal glyph map as a 4-component float volume, for inspection in any viewer.
void addGlyphMapCommand(CLI::App& app);

}  // namespace mvw::app
