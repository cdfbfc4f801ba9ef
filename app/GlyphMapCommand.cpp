#include "GlyphMapCommand.h"

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "CliChecks.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/render/GlyphMap.h"

namespace mvw::app {

namespace {

struct GlyphMapOptions {
  std::string output;
  render::GlyphMapSettings settings;
  double voxelMm = 1.0;
};

// `mvw glyphmap -o FILE`: the normal map as a volume (render::glyphMapVolume).
void runGlyphMap(const GlyphMapOptions& o) {
  io::checkVolumeOutput(o.output);
  const render::GlyphMap map = render::makeGlyphMap(o.settings);
  io::writeVolume(render::glyphMapVolume(map, o.voxelMm), o.output);
  std::cout << "wrote " << map.centres.size() << " glyphs of " << 2 * map.radius << " voxels in a "
            << map.size << "^3 map to " << o.output << "\n";
}

}  // namespace

void addGlyphMapCommand(CLI::App& app) {
  auto g = std::make_shared<GlyphMapOptions>();
  CLI::App* cmd =
      app.add_subcommand("glyphmap", "Export the volumetric normal glyph map (NIfTI or MetaImage)");
  cmd->add_option("-o,--output", g->output, "Output file (.nii, .nii.gz, .mha, .mhd)")->required();
  cmd->add_option("--size", g->settings.size, "Voxels per side")->check(CLI::Range(8, 512));
  cmd->add_option("--count", g->settings.count, "Number of glyphs")->check(CLI::Range(1, 255));
  CLI::Option* diameter =
      cmd->add_option("--diameter", g->settings.diameter,
                      "Glyph diameter in map voxels (default: a quarter of the map size, at "
                      "most the renderer's 32)");
  cmd->add_option("--seed", g->settings.seed, "Random seed of the positions")->check(nonNegative());
  cmd->add_option("--voxel-mm", g->voxelMm, "Voxel size written to the file")
      ->check(CLI::Range(1e-3, 1e3));
  cmd->callback([g, diameter] {
    // Another map size scales the default glyph with it (32 voxels in the default 128^3 map):
    // the same 16 glyphs then fill the same fraction of any map.
    if (diameter->count() == 0)
      g->settings.diameter = std::min(g->settings.diameter, g->settings.size / 4.0);
    try {
      runGlyphMap(*g);
    } catch (const InputError&) {
      throw;
    } catch (const Error& e) {
      throw InputError(g->output, e.what());  // impossible glyph requests are bad input
    }
  });
}

}  // namespace mvw::app
