#pragma once
// A synthetic vessel tree with known geometry, for the depth-cued MIP ("angiogram") tests
// and sample: branching tubes of decreasing radius, bright on a dim, noisy background, in
// LPS mm. The root rises from the bottom (inferior) centre; each segment splits in two.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"

namespace mvw {

struct VesselTreeSettings {
  glm::ivec3 dimensions{128, 128, 128};
  double spacingMm = 1.0;
  int generations = 5;         // root = generation 0
  double rootRadiusMm = 4.0;   // children: 0.72 x the parent
  double rootLengthMm = 40.0;  // children: 0.78 x the parent
  double vesselValue = 1000.0;
  double background = 100.0;
  double noiseSigma = 25.0;  // Gaussian, seeded
  std::uint32_t seed = 1;
};

struct VesselSegment {
  glm::dvec3 from, to;  // world mm (LPS)
  double radiusMm = 0.0;
  int generation = 0;
};

struct VesselTree {
  Volume volume;  // float32, centred on the world origin
  std::vector<VesselSegment> segments;
};

VesselTree makeVesselTree(const VesselTreeSettings& settings);

}  // namespace mvw
