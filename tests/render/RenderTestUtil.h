#pragma once
// Shared helpers for the ray caster's GL tests: how they build their volumes (analytic volumes
// sampled at voxel centres, the sample cranium), their context and renderer, and their
// settings; and where a grey range lies on the screen.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>  // the tests use most of core GLM (length, dot, all, clamp)

#include "../support/TestUtil.h"
#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Camera.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/RenderSettings.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::test {

// An axis-aligned grid: voxel (0, 0, 0)'s centre at `origin`, `spacing` mm apart.
inline glm::dmat4 axisGrid(glm::dvec3 origin, glm::dvec3 spacing) {
  return makeWorldFromIndex(origin, spacing, glm::dmat3(1.0));
}

// A one-component volume of type T holding static_cast<T>(f(world position of each voxel
// centre)); f rounds where T is an integer type.
template <class T, class F>
Volume makeVolumeOf(glm::ivec3 dims, const glm::dmat4& worldFromIndex, const F& f) {
  Volume v(dims, 1, scalarTypeOf<T>(), worldFromIndex);
  T* p = v.dataAs<T>();
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) *p++ = static_cast<T>(f(v.worldFromIndexPoint({i, j, k})));
  return v;
}

// A float volume holding f(world position of each voxel centre).
inline Volume makeVolume(glm::ivec3 dims, const glm::dmat4& worldFromIndex,
                         const std::function<float(glm::dvec3)>& f) {
  return makeVolumeOf<float>(dims, worldFromIndex, f);
}

// The sample data's cranium CT, the GL tests' real volume.
inline Volume sampleCranium() { return io::readVolume(sampleData("cranium/cranium.nii.gz")); }

// The GL tests' headless context. Its own framebuffer's size never shows: a renderer draws
// into its own target at the settings' size.
inline std::unique_ptr<render::GlContext> headlessContext() {
  return render::createHeadlessContext({16, 16});
}

// The context first, so that it is made before the renderer and outlives it (base-from-member).
struct HeadlessContextHolder {
  std::unique_ptr<render::GlContext> contextHolder = headlessContext();
};

// A renderer of one volume on a headless context of its own: what most GL tests start from. A
// second renderer of the same test shares its context (`VolumeRenderer b(a.context(), v)`).
class Renderer : private HeadlessContextHolder, public render::VolumeRenderer {
 public:
  explicit Renderer(const Volume& volume,
                    render::GradientSource gradient = render::GradientSource::Auto)
      : render::VolumeRenderer(*contextHolder, volume, gradient) {}
  render::GlContext& context() { return *contextHolder; }
};

// What nearly every GL test sets first; everything else keeps RenderSettings' defaults.
struct Shot {
  render::RenderMode mode = render::RenderMode::Composite;
  glm::ivec2 size{0};                                       // required
  std::optional<render::StandardView> view = std::nullopt;  // unset: the camera's default
  bool jitterOff = false;  // true: no jitter, for exact comparisons
};
inline render::RenderSettings settingsOf(const Shot& shot) {
  render::RenderSettings s;
  s.mode = shot.mode;
  s.size = shot.size;
  if (shot.view) s.camera.view = *shot.view;
  if (shot.jitterOff) s.jitter = false;
  return s;
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

// The block distance maps' definition, for their tests: for every block of a grid of `n`
// blocks (x fastest), the least Chebyshev distance in blocks to a block where `marked(b)`
// holds, at most 255 (255 where none is).
template <class Marked>
std::vector<std::uint8_t> chebyshevDistanceByDefinition(glm::ivec3 n, const Marked& marked) {
  std::vector<glm::ivec3> seeds;
  for (int k = 0, b = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i, ++b)
        if (marked(b)) seeds.emplace_back(i, j, k);
  std::vector<std::uint8_t> d(static_cast<std::size_t>(n.x) * n.y * n.z);
  for (int k = 0, b = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i, ++b) {
        int expected = 255;
        for (const glm::ivec3& s : seeds)
          expected = std::min(expected,
                              std::max({std::abs(s.x - i), std::abs(s.y - j), std::abs(s.z - k)}));
        d[static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(expected);
      }
  return d;
}

}  // namespace mvw::test
