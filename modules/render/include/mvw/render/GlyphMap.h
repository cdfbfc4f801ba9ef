#pragma once
// The volumetric normal map of Seipel (2007), section 3.1: a periodic RGBA volume holding
// spherical normal glyphs at seeded random, non-overlapping positions. Inside a glyph RGB is
// the unit normal pointing away from its centre and A the distance to the centre divided by
// the glyph radius (0..1, eq. 2 needs it); outside every glyph RGB = 0 and A = -1. The map
// repeats along all axes (positions and overlap tests wrap around), so the renderer tiles
// it over the volume with GL_REPEAT.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace mvw::render {

struct GlyphMapSettings {
  int size = 128;           // voxels per side
  int count = 16;
  double diameter = 32.0;   // voxels
  std::uint32_t seed = 1;
};

struct GlyphMap {
  int size = 0;
  double radius = 0.0;                // voxels
  std::vector<glm::dvec3> centres;    // voxel coordinates, 0..size
  std::vector<glm::vec4> texels;      // size^3, x fastest

  const glm::vec4& at(int i, int j, int k) const;  // periodic
};

// Throws mvw::Error when the glyphs cannot be placed without overlap (too many or too big).
GlyphMap makeGlyphMap(const GlyphMapSettings& settings);

}  // namespace mvw::render
