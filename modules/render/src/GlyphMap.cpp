#include "mvw/render/GlyphMap.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>

#include "mvw/core/Check.h"
#include "mvw/core/Error.h"

namespace mvw::render {

namespace {

// Shortest offset from b to a on the periodic lattice of period n.
glm::dvec3 periodicDelta(const glm::dvec3& a, const glm::dvec3& b, double n) {
  glm::dvec3 d = a - b;
  for (int c = 0; c < 3; ++c) d[c] -= n * std::round(d[c] / n);
  return d;
}

// Calls f(index, offset) for every site of a periodic lattice (sites at (v + 0.5) * step, count
// per side, period count * step) whose offset from `centre` is at most `reach`; index is the
// site's wrapped linear index, x fastest.
template <class F>
void forEachSiteNear(const glm::dvec3& centre, double reach, double step, int count, F f) {
  const double period = step * count;
  const glm::ivec3 base(glm::floor(centre / step));
  const int r = static_cast<int>(std::ceil(reach / step)) + 1;
  auto wrap = [&](int x) { return ((x % count) + count) % count; };
  for (int dk = -r; dk <= r; ++dk)
    for (int dj = -r; dj <= r; ++dj)
      for (int di = -r; di <= r; ++di) {
        const glm::ivec3 v = base + glm::ivec3(di, dj, dk);
        const glm::dvec3 d = periodicDelta((glm::dvec3(v) + 0.5) * step, centre, period);
        if (glm::length(d) > reach) continue;
        f((static_cast<std::size_t>(wrap(v.z)) * count + wrap(v.y)) * count + wrap(v.x), d);
      }
}

}  // namespace

const glm::vec4& GlyphMap::at(int i, int j, int k) const {
  auto wrap = [&](int v) { return ((v % size) + size) % size; };
  return texels[(static_cast<std::size_t>(wrap(k)) * size + wrap(j)) * size + wrap(i)];
}

namespace {

// 160 voxels (80^3 cells, 512 kB: still cache-sized) keep the cell clearance at 1/8 of the
// spacing, so glyphs can fill 3/4 of it and still jitter.
constexpr int kBlueNoiseMapSize = 160;

int cellSizeOf(int size) { return size % 2 == 0 ? 2 : 1; }  // a 64^3 grid for a 128^3 map

std::string voxels(double v) {
  std::ostringstream o;
  o << std::setprecision(3) << v;
  return o.str();
}

// The jittered BCC lattice (see GlyphPlacement::BlueNoise): the whole lattice shifted by a
// seeded offset, each site by a seeded offset within a ball of the jitter radius.
std::vector<glm::dvec3> blueNoiseCentres(const GlyphMapSettings& s) {
  const double jitter = blueNoiseJitter(s.size, s.diameter);
  if (jitter < 0.0)
    throw Error("a glyph diameter of " + voxels(s.diameter) +
                " map voxels does not fit a spacing of " + voxels(blueNoiseSpacing(s.size)) +
                " (at most " + voxels(blueNoiseSpacing(s.size) - glyphClearance(s.size)) + ")");
  const double edge = double(s.size) / kBlueNoiseCubes;
  std::mt19937 rng(s.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const glm::dvec3 shift = (glm::dvec3(unit(rng), unit(rng), unit(rng)) + 1.0) * (0.5 * edge);
  std::vector<glm::dvec3> centres;
  for (int k = 0; k < kBlueNoiseCubes; ++k)
    for (int j = 0; j < kBlueNoiseCubes; ++j)
      for (int i = 0; i < kBlueNoiseCubes; ++i)
        for (double body : {0.0, 0.5}) {
          glm::dvec3 offset;
          do offset = glm::dvec3(unit(rng), unit(rng), unit(rng));
          while (glm::dot(offset, offset) > 1.0);
          glm::dvec3 c = (glm::dvec3(i, j, k) + body) * edge + shift + jitter * offset;
          for (int a = 0; a < 3; ++a) c[a] -= s.size * std::floor(c[a] / s.size);
          centres.push_back(c);
        }
  return centres;
}

// The paper's map: rejection sampling at random positions. A glyph may not come closer than
// one diameter plus one cell diagonal to another, measured on the periodic lattice, so no
// cell is reached by two glyphs.
std::vector<glm::dvec3> paperCentres(const GlyphMapSettings& s) {
  const double n = s.size;
  std::mt19937 rng(s.seed);
  std::uniform_real_distribution<double> position(0.0, n);
  const double minDistance = s.diameter + glyphClearance(s.size) + 1e-6;
  std::vector<glm::dvec3> centres;
  for (int attempts = 0; static_cast<int>(centres.size()) < s.count; ++attempts) {
    if (attempts > 200000)
      throw Error("cannot place " + std::to_string(s.count) + " glyphs of " + voxels(s.diameter) +
                  " voxels without overlap in a " + std::to_string(s.size) +
                  "^3 map (random placement fitted " + std::to_string(centres.size()) +
                  "; use fewer or smaller glyphs, or the blue-noise placement)");
    const glm::dvec3 c(position(rng), position(rng), position(rng));
    bool free = true;
    for (const auto& other : centres)
      free &= glm::length(periodicDelta(c, other, n)) >= minDistance;
    if (free) centres.push_back(c);
  }
  return centres;
}

}  // namespace

double blueNoiseSpacing(int size) {
  return double(size) / kBlueNoiseCubes * std::sqrt(3.0) / 2.0;  // half the cube's diagonal
}

double glyphClearance(int size) { return std::sqrt(3.0) * cellSizeOf(size); }

double blueNoiseJitter(int size, double diameter) {
  const double spacing = blueNoiseSpacing(size);
  // 1e-6: the strict inequality the cells rely on (see paperCentres).
  const double room = 0.5 * (spacing - diameter - glyphClearance(size) - 2e-6);
  return std::min(room, 0.15 * spacing);
}

double blueNoiseCoverage(int size, double diameter) {
  return std::sqrt(5.0) / 4.0 * size / kBlueNoiseCubes +
         std::max(0.0, blueNoiseJitter(size, diameter));
}

glm::dmat3 glyphMapRotation(GlyphPlacement placement) {
  if (placement == GlyphPlacement::Paper) return glm::dmat3(1.0);
  // 37 degrees about (1, 2, 3): no lattice direction of low index lies along a patient axis.
  return glm::dmat3(
      glm::rotate(glm::dmat4(1.0), glm::radians(37.0), glm::normalize(glm::dvec3(1, 2, 3))));
}

GlyphMapSettings blueNoiseGlyphMap(double spacingMm, double diameterMm, std::uint32_t seed) {
  if (!(spacingMm > 0.0) || !(diameterMm > 0.0))
    throw Error("glyph spacing and diameter must be positive");
  GlyphMapSettings s;
  s.placement = GlyphPlacement::BlueNoise;
  s.size = kBlueNoiseMapSize;
  s.seed = seed;
  s.count = 2 * kBlueNoiseCubes * kBlueNoiseCubes * kBlueNoiseCubes;
  s.diameter = diameterMm * blueNoiseSpacing(s.size) / spacingMm;
  if (blueNoiseJitter(s.size, s.diameter) < 0.0) {
    std::ostringstream o;
    o << std::setprecision(3) << "a glyph diameter of " << diameterMm
      << " mm does not fit a spacing of " << spacingMm << " mm (at most "
      << maxBlueNoiseDiameterMm(spacingMm) << " mm)";
    throw Error(o.str());
  }
  return s;
}

double maxBlueNoiseDiameterMm(double spacingMm) {
  const int size = kBlueNoiseMapSize;
  return spacingMm * (1.0 - glyphClearance(size) / blueNoiseSpacing(size)) - 1e-6;
}

GlyphMap makeGlyphMap(const GlyphMapSettings& s, bool texels) {
  if (s.size < 8 || s.size > 512) throw Error("glyph map size must be 8..512 voxels");
  if (s.placement == GlyphPlacement::Paper && (s.count < 1 || s.count > 255))
    throw Error("glyph count must be 1..255");
  if (!(s.diameter >= 2.0) || s.diameter > s.size / 2.0)
    throw Error("glyph diameter must be 2 .. half the map size (" + std::to_string(s.size / 2) +
                ") voxels");
  GlyphMap map;
  map.size = s.size;
  map.radius = s.diameter / 2.0;
  map.cellSize = cellSizeOf(s.size);
  const double halfDiagonal = 0.5 * glyphClearance(s.size);
  map.centres = s.placement == GlyphPlacement::BlueNoise ? blueNoiseCentres(s) : paperCentres(s);
  // A glyph reaches into a cell only if the cell's centre lies within radius + half a diagonal
  // of its centre; then, by the clearance, no other glyph reaches that cell.
  const int cells = s.size / map.cellSize;
  map.cells.assign(static_cast<std::size_t>(cells) * cells * cells, 0);
  for (std::size_t g = 0; g < map.centres.size(); ++g)
    forEachSiteNear(
        map.centres[g], map.radius + halfDiagonal, map.cellSize, cells,
        [&](std::size_t i, const glm::dvec3&) { map.cells[i] = static_cast<std::uint8_t>(g + 1); });
  if (!texels) return map;
  // Texel centres sit at integer + 0.5 in map coordinates.
  map.texels.assign(static_cast<std::size_t>(s.size) * s.size * s.size, glm::vec4(0, 0, 0, -1));
  for (const auto& c : map.centres)
    forEachSiteNear(c, map.radius, 1.0, s.size, [&](std::size_t i, const glm::dvec3& d) {
      const double r = glm::length(d);
      const glm::dvec3 normal = r > 1e-9 ? d / r : glm::dvec3(0, 0, 1);
      map.texels[i] = glm::vec4(glm::vec3(normal), static_cast<float>(r / map.radius));
    });
  return map;
}

Volume glyphMapVolume(const GlyphMap& map, double voxelMm) {
  MVW_CHECK(map.texels.size() == static_cast<std::size_t>(map.size) * map.size * map.size);
  Volume v({map.size, map.size, map.size}, 4, ScalarType::Float32,
           makeWorldFromIndex(glm::dvec3(0.0), glm::dvec3(voxelMm), glm::dmat3(1.0)));
  std::memcpy(v.data(), map.texels.data(), v.byteSize());
  v.metadata().seriesDescription = "mvw glyph normal map";
  return v;
}

}  // namespace mvw::render
