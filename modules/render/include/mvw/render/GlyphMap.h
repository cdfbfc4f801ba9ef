#pragma once
// The volumetric normal map of Seipel (2007), section 3.1: a periodic RGBA volume holding
// spherical normal glyphs at seeded random, non-overlapping positions. Inside a glyph RGB is
// the unit normal pointing away from its centre and A the distance to the centre divided by
// the glyph radius (0..1, eq. 2 needs it); outside every glyph RGB = 0 and A = -1. The map
// repeats along all axes (positions and overlap tests wrap around), so the renderer tiles
// it over the volume.
//
// The renderer reads the same map in a compact form (the texels are for export and tests): the
// map cut into cells of `cellSize` voxels, each holding which glyph reaches into it. Glyphs
// keep a clearance of one cell diagonal, so at most one glyph reaches any cell, and the
// shader evaluates N_G and A exactly from that glyph's centre: the values the RGBA texels
// hold at their centres, at every point in between too, from a 64^3 byte grid that stays in
// a CPU's cache instead of an 8 MB RGBA volume that does not (glyph shading cost 1.7x the
// unshaded composite frame with the RGBA texture on llvmpipe).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace mvw::render {

struct GlyphMapSettings {
  int size = 128;          // voxels per side
  int count = 16;          // at most 255 (one byte per cell names the glyph)
  double diameter = 32.0;  // voxels
  std::uint32_t seed = 1;
};

struct GlyphMap {
  int size = 0;
  double radius = 0.0;              // voxels
  std::vector<glm::dvec3> centres;  // voxel coordinates, 0..size
  std::vector<glm::vec4> texels;    // size^3, x fastest (empty if not asked for)
  int cellSize = 1;                 // voxels per cell side (divides size)
  std::vector<std::uint8_t> cells;  // (size / cellSize)^3, x fastest: 1 + glyph index, 0 none

  const glm::vec4& at(int i, int j, int k) const;  // periodic
};

// Throws mvw::Error when the glyphs cannot be placed without overlap (too many or too big).
// texels = false leaves `texels` empty: the renderer needs only the centres and cells.
GlyphMap makeGlyphMap(const GlyphMapSettings& settings, bool texels = true);

}  // namespace mvw::render
