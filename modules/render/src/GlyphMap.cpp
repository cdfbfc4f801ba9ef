#include "mvw/render/GlyphMap.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <random>
#include <string>

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

GlyphMap makeGlyphMap(const GlyphMapSettings& s, bool texels) {
  if (s.size < 8 || s.size > 512) throw Error("glyph map size must be 8..512 voxels");
  if (s.count < 1 || s.count > 255) throw Error("glyph count must be 1..255");
  if (!(s.diameter >= 2.0) || s.diameter > s.size / 2.0)
    throw Error("glyph diameter must be 2 .. half the map size (" + std::to_string(s.size / 2) +
                ") voxels");
  GlyphMap map;
  map.size = s.size;
  map.radius = s.diameter / 2.0;
  const double n = s.size;
  std::mt19937 rng(s.seed);
  std::uniform_real_distribution<double> position(0.0, n);
  // Cells of 2 voxels where the size allows (a 64^3 grid for the default map), else 1.
  map.cellSize = s.size % 2 == 0 ? 2 : 1;
  const double halfDiagonal = 0.5 * std::sqrt(3.0) * map.cellSize;
  // Rejection sampling: a glyph may not come closer than one diameter plus one cell diagonal
  // to another, measured on the periodic lattice, so no cell is reached by two glyphs.
  const double minDistance = s.diameter + 2.0 * halfDiagonal + 1e-6;
  for (int attempts = 0; static_cast<int>(map.centres.size()) < s.count; ++attempts) {
    if (attempts > 200000)
      throw Error("cannot place " + std::to_string(s.count) + " glyphs of " +
                  std::to_string(s.diameter) + " voxels without overlap in a " +
                  std::to_string(s.size) + "^3 map");
    const glm::dvec3 c(position(rng), position(rng), position(rng));
    bool free = true;
    for (const auto& other : map.centres)
      free &= glm::length(periodicDelta(c, other, n)) >= minDistance;
    if (free) map.centres.push_back(c);
  }
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

}  // namespace mvw::render
