#include "mvw/core/Volume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "mvw/core/Check.h"

namespace mvw {

Volume::Volume(glm::ivec3 dims, int components, ScalarType type, const glm::dmat4& worldFromIndex)
    : dims_(dims), components_(components), type_(type), worldFromIndex_(worldFromIndex) {
  MVW_CHECK(dims.x > 0 && dims.y > 0 && dims.z > 0);
  MVW_CHECK(components > 0);
  bytes_.resize(valueCount() * scalarSize(type));
}

std::size_t Volume::voxelCount() const {
  return static_cast<std::size_t>(dims_.x) * static_cast<std::size_t>(dims_.y) *
         static_cast<std::size_t>(dims_.z);
}

std::size_t Volume::linearIndex(int i, int j, int k) const {
  return ((static_cast<std::size_t>(k) * dims_.y + j) * dims_.x + i) * components_;
}

double Volume::value(int i, int j, int k, int component) const {
  const std::size_t at = linearIndex(i, j, k) + component;
  return dispatchScalar(type_, [&](auto t) {
    return static_cast<double>(reinterpret_cast<const decltype(t)*>(bytes_.data())[at]);
  });
}

void Volume::setValue(int i, int j, int k, int component, double v) {
  const std::size_t at = linearIndex(i, j, k) + component;
  dispatchScalar(type_, [&](auto t) {
    reinterpret_cast<decltype(t)*>(bytes_.data())[at] = static_cast<decltype(t)>(v);
    return 0;
  });
}

glm::dvec3 Volume::origin() const { return glm::dvec3(worldFromIndex_[3]); }

double Volume::smallestSpacing() const {
  const glm::dvec3 s = spacing();
  return std::min({s.x, s.y, s.z});
}

glm::dvec3 Volume::spacing() const {
  return {glm::length(glm::dvec3(worldFromIndex_[0])), glm::length(glm::dvec3(worldFromIndex_[1])),
          glm::length(glm::dvec3(worldFromIndex_[2]))};
}

glm::dmat3 Volume::direction() const {
  const glm::dvec3 s = spacing();
  glm::dmat3 d;
  for (int c = 0; c < 3; ++c)
    d[c] = s[c] > 0 ? glm::dvec3(worldFromIndex_[c]) / s[c] : glm::dvec3(0);
  return d;
}

glm::dvec3 Volume::worldFromIndexPoint(const glm::dvec3& ijk) const {
  return glm::dvec3(worldFromIndex_ * glm::dvec4(ijk, 1.0));
}

std::pair<double, double> Volume::valueRange() const {
  if (bytes_.empty()) return {0.0, 0.0};
  return dispatchScalar(type_, [&](auto t) {
    using T = decltype(t);
    const T* p = reinterpret_cast<const T*>(bytes_.data());
    const std::size_t n = valueCount();
    if constexpr (std::is_integral_v<T>) {
      // No NaN or infinity: the extremes in the values' own type, a loop the compiler
      // vectorises (every voxel converted to double took half a second on a 512 x 512 x 432 CT).
      T lo = p[0], hi = p[0];
      for (std::size_t i = 1; i < n; ++i) {
        lo = p[i] < lo ? p[i] : lo;
        hi = p[i] > hi ? p[i] : hi;
      }
      return std::pair<double, double>{static_cast<double>(lo), static_cast<double>(hi)};
    } else {
      // In the values' own type too (widening to double keeps every comparison).
      T lo = std::numeric_limits<T>::infinity();
      T hi = -lo;
      for (std::size_t i = 0; i < n; ++i) {
        const T v = p[i];
        if (std::isinf(v)) continue;  // the range is always finite (readers clamp +-inf)
        if (v < lo) lo = v;           // NaN compares false both ways and is skipped
        if (v > hi) hi = v;
      }
      if (lo > hi) return std::pair<double, double>{0.0, 0.0};  // all NaN
      return std::pair<double, double>{static_cast<double>(lo), static_cast<double>(hi)};
    }
  });
}

Volume Volume::converted(ScalarType type, double slope, double intercept) const {
  Volume out(dims_, components_, type, worldFromIndex_);
  out.meta_ = meta_;
  const std::size_t n = valueCount();
  dispatchScalar(type_, [&](auto s) {
    using S = decltype(s);
    const S* src = reinterpret_cast<const S*>(bytes_.data());
    return dispatchScalar(type, [&](auto d) {
      using D = decltype(d);
      D* dst = reinterpret_cast<D*>(out.bytes_.data());
      for (std::size_t i = 0; i < n; ++i)
        dst[i] = static_cast<D>(static_cast<double>(src[i]) * slope + intercept);
      return 0;
    });
  });
  return out;
}

glm::dmat4 makeWorldFromIndex(const glm::dvec3& origin, const glm::dvec3& spacing,
                              const glm::dmat3& direction) {
  glm::dmat4 m(1.0);
  for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(direction[c] * spacing[c], 0.0);
  m[3] = glm::dvec4(origin, 1.0);
  return m;
}

}  // namespace mvw
