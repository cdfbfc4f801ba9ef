#pragma once
// Shared helpers for the ray caster's GL tests: analytic volumes sampled at voxel centres, and
// where a grey range lies on the screen.
#include <functional>

#include <glm/glm.hpp>  // the tests use most of core GLM (length, dot, all, clamp)

#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"

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
