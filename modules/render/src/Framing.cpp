#include "mvw/render/Framing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace mvw::render {

FramingSphere framingSphere(const Volume& volume) {
  const glm::dmat4& worldFromIndex = volume.worldFromIndex();
  const glm::dvec3 dims(volume.dimensions());
  const glm::dvec3 corner0(worldFromIndex * glm::dvec4(-0.5, -0.5, -0.5, 1.0));
  const glm::dvec3 corner1(worldFromIndex * glm::dvec4(dims - 0.5, 1.0));
  // The diagonal from the spacing rather than the corners: the same length for an orthonormal
  // direction matrix, and the value every golden image was rendered with.
  return {0.5 * (corner0 + corner1), 0.5 * glm::length(dims * volume.spacing())};
}

std::pair<glm::dvec3, glm::dvec3> worldBounds(const Volume& volume, const glm::dmat4& worldFrom) {
  const glm::dvec3 n(volume.dimensions());
  glm::dvec3 lo(1e300), hi(-1e300);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 ijk((c & 1) ? n.x - 0.5 : -0.5, (c & 2) ? n.y - 0.5 : -0.5,
                         (c & 4) ? n.z - 0.5 : -0.5);
    const glm::dvec3 p(worldFrom * glm::dvec4(volume.worldFromIndexPoint(ijk), 1.0));
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return {lo, hi};
}

double defaultStepMm(const Volume& volume) { return 0.5 * volume.smallestSpacing(); }

PatientCrop::PatientCrop(const Volume& volume) {
  // The assignment of index axes to patient axes that follows the direction cosines best
  // (of the six permutations), so even a 45-degree oblique volume gets each axis once.
  const glm::dmat3 d = volume.direction();
  std::array<int, 3> perm{0, 1, 2}, best = perm;
  double bestScore = -1.0;
  do {
    const double score =
        std::abs(d[0][perm[0]]) + std::abs(d[1][perm[1]]) + std::abs(d[2][perm[2]]);
    if (score > bestScore + 1e-12) bestScore = score, best = perm;
  } while (std::next_permutation(perm.begin(), perm.end()));
  for (int t = 0; t < 3; ++t) {
    worldAxis_[t] = best[static_cast<std::size_t>(t)];
    reversed_[t] = d[t][worldAxis_[t]] < 0.0;
    for (int w = 0; w < 3; ++w)
      if (w != worldAxis_[t] && std::abs(d[t][w]) > 1e-9) axisAligned_ = false;
  }
  std::tie(boxMin_, boxMax_) = worldBounds(volume);
}

std::pair<glm::dvec3, glm::dvec3> PatientCrop::textureBox(const glm::dvec3& lpsMin,
                                                          const glm::dvec3& lpsMax) const {
  glm::dvec3 lo, hi;
  for (int t = 0; t < 3; ++t) {
    const double a = std::clamp(lpsMin[worldAxis_[t]], 0.0, 1.0);
    const double b = std::clamp(lpsMax[worldAxis_[t]], 0.0, 1.0);
    lo[t] = reversed_[t] ? 1.0 - b : a;
    hi[t] = reversed_[t] ? 1.0 - a : b;
  }
  return {lo, hi};
}

std::pair<glm::dvec3, glm::dvec3> PatientCrop::worldBox(const glm::dvec3& lpsMin,
                                                        const glm::dvec3& lpsMax) const {
  const glm::dvec3 extent = boxMax_ - boxMin_;
  return {boxMin_ + glm::clamp(lpsMin, 0.0, 1.0) * extent,
          boxMin_ + glm::clamp(lpsMax, 0.0, 1.0) * extent};
}

std::pair<glm::dvec3, glm::dvec3> PatientCrop::fractionsFromMm(const glm::dvec3& minMm,
                                                               const glm::dvec3& maxMm) const {
  const glm::dvec3 extent = glm::max(boxMax_ - boxMin_, glm::dvec3(1e-9));
  return {glm::clamp((minMm - boxMin_) / extent, 0.0, 1.0),
          glm::clamp((maxMm - boxMin_) / extent, 0.0, 1.0)};
}

}  // namespace mvw::render
