#pragma once
// Shared helpers for the ray caster's GL tests: analytic volumes sampled at voxel centres, and
// where a grey range lies on the screen.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <utility>

#include <glm/glm.hpp>  // the tests use most of core GLM (length, dot, all, clamp)

#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/render/Camera.h"

namespace mvw::test {

// A float volume holding f(world position of each voxel centre).
inline Volume makeVolume(glm::ivec3 dims, const glm::dmat4& worldFromIndex,
                         const std::function<float(glm::dvec3)>& f) {
  Volume v(dims, 1, ScalarType::Float32, worldFromIndex);
  float* p = v.dataAs<float>();
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) *p++ = f(v.worldFromIndexPoint({i, j, k}));
  return v;
}

// Where a ray enters and leaves the index box [lo, hi] (voxel edges: -0.5 .. dims - 0.5 for the
// whole volume) enlarged by `grow` voxels, as distances (mm) from its origin, from 0 on (the
// ray starts on the near plane); nullopt where it misses.
inline std::optional<std::pair<double, double>> rayThroughIndexBox(const Volume& v,
                                                                   const render::WorldRay& ray,
                                                                   glm::dvec3 lo, glm::dvec3 hi,
                                                                   double grow = 0.0) {
  const glm::dmat4 indexFromWorld = glm::inverse(v.worldFromIndex());
  const glm::dvec3 o(indexFromWorld * glm::dvec4(ray.origin, 1.0));
  const glm::dvec3 d(indexFromWorld * glm::dvec4(ray.direction, 0.0));
  double tNear = 0.0, tFar = 1e30;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (o[a] < lo[a] - grow || o[a] > hi[a] + grow) return std::nullopt;
      continue;
    }
    double t0 = (lo[a] - grow - o[a]) / d[a], t1 = (hi[a] + grow - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    tNear = std::max(tNear, t0);
    tFar = std::min(tFar, t1);
  }
  if (tNear >= tFar) return std::nullopt;
  return std::pair{tNear, tFar};
}

struct Centroid {
  double x = 0, y = 0;
  int n = 0;
};
// Centroid of the pixels whose red channel lies in [lo, hi].
inline Centroid centroidOf(const Image& img, int lo, int hi) {
  Centroid c;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const int g = img.pixel(x, y)[0];
      if (g >= lo && g <= hi) {
        c.x += x;
        c.y += y;
        ++c.n;
      }
    }
  if (c.n) {
    c.x /= c.n;
    c.y /= c.n;
  }
  return c;
}

}  // namespace mvw::test
