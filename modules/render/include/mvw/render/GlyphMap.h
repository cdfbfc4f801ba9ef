#pragma once
// The volumetric normal map of Seipel (2007), section 3.1: a periodic RGBA volume holding
// spherical normal glyphs at seeded, non-overlapping positions. Inside a glyph RGB is
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

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mvw/core/Volume.h"

namespace mvw::render {

// Where the glyphs go.
// Paper: the seed paper's own map (16 glyphs of 32 voxels in 128^3 at random positions,
// rejection sampling), kept so its figures can be reproduced. Random positions leave holes:
// a 15 mm lesion on a surface meets about one glyph disc at the paper's density.
// BlueNoise: a jittered body-centred cubic lattice, 5 x 5 x 5 cubes (250 glyphs) per period,
// every site moved by a seeded random offset in a ball. The lattice packs glyphs as densely
// as their spacing allows (BCC: 68 % of space for touching spheres, near the 74 % of the
// densest packing, with a period of 5.8 spacings instead of FCC's 4.2, so repeats are less
// visible), guarantees that every point lies within blueNoiseCoverage() of a centre, and the
// jitter breaks the regular rows a reader would otherwise see.
enum class GlyphPlacement { Paper, BlueNoise };

struct GlyphMapSettings {
  int size = 128;          // voxels per side
  int count = 16;          // Paper only: at most 255 (one byte per cell names the glyph)
  double diameter = 32.0;  // voxels
  std::uint32_t seed = 1;
  GlyphPlacement placement = GlyphPlacement::Paper;
};

// The blue-noise lattice: cubes per period side, and the nominal centre spacing (nearest
// neighbour distance, before jitter) in map voxels for a map of `size` voxels.
inline constexpr int kBlueNoiseCubes = 5;
double blueNoiseSpacing(int size);
// The clearance two glyphs keep (one cell diagonal, see GlyphMap::cells), in map voxels.
double glyphClearance(int size);
// The jitter radius of a blue-noise map (map voxels): what the spacing leaves after the
// diameter and the clearance, at most 0.15 spacing. Negative: the diameter does not fit.
double blueNoiseJitter(int size, double diameter);
// The largest distance from any point of a blue-noise map to its nearest glyph centre (map
// voxels): the BCC lattice's covering radius (sqrt(5)/4 of the cube edge) plus the jitter.
double blueNoiseCoverage(int size, double diameter);

// How the map is turned on the patient (world mm to map axes, before scaling): the identity
// for the paper's map; for the blue-noise lattice a fixed oblique rotation, because an axial
// cut (the most common one) parallel to a lattice layer meets every glyph at the same depth:
// all bumps the same size, or none, depending on where the cut falls.
glm::dmat3 glyphMapRotation(GlyphPlacement placement);

// A blue-noise map for glyphs of `diameterMm` whose centres are `spacingMm` apart on the
// patient; the map's voxel size follows from the spacing (voxels per mm: see
// glyphMapVoxelsPerMm). Throws mvw::Error when the diameter does not fit the spacing.
GlyphMapSettings blueNoiseGlyphMap(double spacingMm, double diameterMm, std::uint32_t seed);
// The largest glyph diameter (mm) a blue-noise spacing holds.
double maxBlueNoiseDiameterMm(double spacingMm);

struct GlyphMap {
  int size = 0;
  double radius = 0.0;              // voxels
  std::vector<glm::dvec3> centres;  // voxel coordinates, 0..size
  std::vector<glm::vec4> texels;    // size^3, x fastest (empty if not asked for)
  int cellSize = 1;                 // voxels per cell side (divides size)
  std::vector<std::uint8_t> cells;  // (size / cellSize)^3, x fastest: 1 + glyph index, 0 none

  const glm::vec4& at(int i, int j, int k) const;  // periodic
};

// Throws mvw::Error when the glyphs cannot be placed without overlap (too many or too big);
// the message says what would fit.
// texels = false leaves `texels` empty: the renderer needs only the centres and cells.
GlyphMap makeGlyphMap(const GlyphMapSettings& settings, bool texels = true);

// The map's texels as a volume for any NIfTI/MetaImage viewer (`mvw glyphmap`): 4 float
// components (RGB normal, A distance to the glyph centre / radius, -1 outside), cubic voxels of
// `voxelMm` from the origin, axes along LPS, described as "mvw glyph normal map".
Volume glyphMapVolume(const GlyphMap& map, double voxelMm);

}  // namespace mvw::render
