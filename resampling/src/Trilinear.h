#pragma once
// Trilinear sampling of a single-component volume (float32, or the stored type) at a continuous
// voxel index, with the gradient of the interpolant (what the metric's analytic derivative needs).
// Internal.
#include <cmath>
#include <cstddef>

#include <glm/vec3.hpp>

namespace mvw::resampling::detail {

// True when p lies within the voxel centres, where trilinear interpolation is defined.
inline bool insideIndex(const glm::ivec3& dims, const glm::dvec3& p) {
  return p.x >= 0.0 && p.y >= 0.0 && p.z >= 0.0 && p.x <= dims.x - 1 && p.y <= dims.y - 1 &&
         p.z <= dims.z - 1;
}

// p must satisfy insideIndex and every dimension must be at least 2. `gradient`, when not
// null, receives d value / d index.
template <typename T>
inline double trilinear(const T* v, const glm::ivec3& dims, const glm::dvec3& p,
                        glm::dvec3* gradient = nullptr) {
  auto base = [](double x, int n, double& f) {
    int i = static_cast<int>(x);  // x >= 0: truncation is floor
    if (i > n - 2) i = n - 2;     // the last centre belongs to the last cell
    f = x - i;
    return i;
  };
  double fx, fy, fz;
  const int i = base(p.x, dims.x, fx), j = base(p.y, dims.y, fy), k = base(p.z, dims.z, fz);
  const std::size_t sx = 1, sy = static_cast<std::size_t>(dims.x),
                    sz = sy * static_cast<std::size_t>(dims.y);
  const T* c = v + static_cast<std::size_t>(i) + j * sy + k * sz;
  const double c000 = c[0], c100 = c[sx], c010 = c[sy], c110 = c[sx + sy];
  const double c001 = c[sz], c101 = c[sx + sz], c011 = c[sy + sz], c111 = c[sx + sy + sz];
  const double c00 = c000 + fx * (c100 - c000), c10 = c010 + fx * (c110 - c010);
  const double c01 = c001 + fx * (c101 - c001), c11 = c011 + fx * (c111 - c011);
  const double c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
  if (gradient) {
    const double dx00 = c100 - c000, dx10 = c110 - c010, dx01 = c101 - c001, dx11 = c111 - c011;
    const double dx0 = dx00 + fy * (dx10 - dx00), dx1 = dx01 + fy * (dx11 - dx01);
    gradient->x = dx0 + fz * (dx1 - dx0);
    gradient->y = (c10 - c00) + fz * ((c11 - c01) - (c10 - c00));
    gradient->z = c1 - c0;
  }
  return c0 + fz * (c1 - c0);
}

}  // namespace mvw::resampling::detail
