#pragma once
// A synthetic volume shared by the registration tests (mutual information, the QA picture and
// registerRigid's refusals): no sample data, so they run in a moment.
#include <cmath>

#include <glm/geometric.hpp>

#include "mvw/core/Volume.h"

namespace mvw::resampling {

// Two smooth blobs: enough structure for MI, smooth enough for a finite-difference check.
inline Volume blobs(const glm::dvec3& offset) {
  Volume v({40, 38, 36}, 1, ScalarType::Float32,
           makeWorldFromIndex({-40, -38, -36}, {2, 2, 2}, glm::dmat3(1.0)));
  for (int k = 0; k < 36; ++k)
    for (int j = 0; j < 38; ++j)
      for (int i = 0; i < 40; ++i) {
        const glm::dvec3 w = v.worldFromIndexPoint({i, j, k}) - offset;
        const double a =
            std::exp(-glm::dot(w - glm::dvec3(8, 0, 0), w - glm::dvec3(8, 0, 0)) / 300.0);
        const double b =
            std::exp(-glm::dot(w + glm::dvec3(0, 12, 6), w + glm::dvec3(0, 12, 6)) / 120.0);
        v.setValue(i, j, k, 0, 100.0 * a + 60.0 * b);
      }
  return v;
}

}  // namespace mvw::resampling
