#include "mvw/core/VesselPhantom.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "mvw/core/Error.h"

namespace mvw {

namespace {

double distanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

}  // namespace

VesselTree makeVesselTree(const VesselTreeSettings& s) {
  if (glm::any(glm::lessThan(s.dimensions, glm::ivec3(8))) || s.generations < 1 ||
      s.generations > 12 || !(s.spacingMm > 0) || !(s.rootRadiusMm > 0) || !(s.rootLengthMm > 0))
    throw Error("invalid vessel phantom settings");
  const glm::dvec3 extent = glm::dvec3(s.dimensions - 1) * s.spacingMm;
  VesselTree tree;
  tree.volume = Volume(s.dimensions, 1, ScalarType::Float32,
                       makeWorldFromIndex(-0.5 * extent, glm::dvec3(s.spacingMm), glm::dmat3(1.0)));
  std::mt19937 rng(s.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  // Grow the tree: a queue of (start, direction, length, radius, generation).
  struct Bud {
    glm::dvec3 start, direction;
    double length, radius;
    int generation;
  };
  std::vector<Bud> buds = {
      {{0.0, 0.0, -0.45 * extent.z}, {0.0, 0.0, 1.0}, s.rootLengthMm, s.rootRadiusMm, 0}};
  const glm::dvec3 lo = -0.45 * extent, hi = 0.45 * extent;
  while (!buds.empty()) {
    const Bud bud = buds.back();
    buds.pop_back();
    const glm::dvec3 end = glm::clamp(bud.start + bud.direction * bud.length, lo, hi);
    tree.segments.push_back({bud.start, end, bud.radius, bud.generation});
    if (bud.generation + 1 >= s.generations) continue;
    // Two children, turned 25..45 degrees away on opposite sides about a random axis
    // perpendicular to the parent.
    glm::dvec3 helper = std::abs(bud.direction.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    glm::dvec3 axis = glm::normalize(glm::cross(bud.direction, helper));
    const double spin = unit(rng) * 2.0 * 3.14159265358979;
    axis = glm::dvec3(glm::rotate(glm::dmat4(1.0), spin, bud.direction) * glm::dvec4(axis, 0.0));
    for (double side : {-1.0, 1.0}) {
      const double angle = side * glm::radians(25.0 + 20.0 * unit(rng));
      const glm::dvec3 dir = glm::normalize(
          glm::dvec3(glm::rotate(glm::dmat4(1.0), angle, axis) * glm::dvec4(bud.direction, 0.0)));
      buds.push_back({end, dir, bud.length * 0.78, bud.radius * 0.72, bud.generation + 1});
    }
  }

  // Rasterise: the dim background, then each tube with a one-voxel soft edge, then noise.
  float* v = tree.volume.dataAs<float>();
  std::fill(v, v + tree.volume.voxelCount(), static_cast<float>(s.background));
  const glm::dmat4 indexFromWorld = glm::inverse(tree.volume.worldFromIndex());
  const glm::ivec3 d = s.dimensions;
  for (const auto& seg : tree.segments) {
    const double reach = seg.radiusMm + s.spacingMm;
    const glm::dvec3 a =
        glm::dvec3(indexFromWorld * glm::dvec4(glm::min(seg.from, seg.to) - reach, 1.0));
    const glm::dvec3 b =
        glm::dvec3(indexFromWorld * glm::dvec4(glm::max(seg.from, seg.to) + reach, 1.0));
    const glm::ivec3 i0 = glm::max(glm::ivec3(glm::floor(a)), glm::ivec3(0));
    const glm::ivec3 i1 = glm::min(glm::ivec3(glm::ceil(b)), d - 1);
    for (int k = i0.z; k <= i1.z; ++k)
      for (int j = i0.y; j <= i1.y; ++j)
        for (int i = i0.x; i <= i1.x; ++i) {
          const double dist =
              distanceToSegment(tree.volume.worldFromIndexPoint({i, j, k}), seg.from, seg.to);
          const double inside = std::clamp((seg.radiusMm - dist) / s.spacingMm + 0.5, 0.0, 1.0);
          float& out = v[tree.volume.linearIndex(i, j, k)];
          out = std::max(
              out, static_cast<float>(s.background + (s.vesselValue - s.background) * inside));
        }
  }
  std::normal_distribution<double> noise(0.0, s.noiseSigma);
  for (std::size_t n = 0; n < tree.volume.voxelCount(); ++n) v[n] += static_cast<float>(noise(rng));
  tree.volume.metadata().modality = "OT";
  tree.volume.metadata().seriesDescription = "mvw synthetic vessel tree";
  return tree;
}

}  // namespace mvw
