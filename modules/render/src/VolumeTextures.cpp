#include "VolumeTextures.h"

#include <algorithm>
#include <string>
#include <thread>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "TextureUpload.h"
#include "mvw/core/Error.h"

namespace mvw::render::detail {

namespace {

// Central differences on the voxel grid with physical spacing (one-sided at the border),
// turned into world (LPS) directions with the direction matrix: the seed's gradient volume.
// The fourth component carries the functional attribute for glyph shading (see
// GlyphTextures::updateBeta); shaders take the magnitude from the vector.
std::vector<float> gradientOf(const std::vector<float>& v, glm::ivec3 d, const glm::dvec3& spacing,
                              const glm::dmat3& direction) {
  std::vector<float> g(v.size() * 4);
  auto at = [&](int i, int j, int k) {
    return v[(static_cast<std::size_t>(k) * d.y + j) * d.x + i];
  };
  auto work = [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          // Central differences along each axis, averaged over the 3 x 3 neighbours across it
          // with weights 1 2 1 (Sobel): 8-bit data then shade without contour terraces.
          glm::dvec3 local(0.0);
          const glm::ivec3 c(i, j, k);
          for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, e = (a + 2) % 3;
            glm::ivec3 lo = c, hi = c;
            lo[a] = std::max(c[a] - 1, 0);
            hi[a] = std::min(c[a] + 1, d[a] - 1);
            if (hi[a] == lo[a]) continue;
            double sum = 0.0, weight = 0.0;
            for (int db = -1; db <= 1; ++db)
              for (int de = -1; de <= 1; ++de) {
                glm::ivec3 p = lo, q = hi;
                p[b] = q[b] = std::clamp(c[b] + db, 0, d[b] - 1);
                p[e] = q[e] = std::clamp(c[e] + de, 0, d[e] - 1);
                const double w = (db == 0 ? 2.0 : 1.0) * (de == 0 ? 2.0 : 1.0);
                sum += w * (at(q.x, q.y, q.z) - at(p.x, p.y, p.z));
                weight += w;
              }
            local[a] = sum / weight / ((hi[a] - lo[a]) * spacing[a]);
          }
          const glm::dvec3 w = direction * local;
          float* out = &g[((static_cast<std::size_t>(k) * d.y + j) * d.x + i) * 4];
          out[0] = static_cast<float>(w.x);
          out[1] = static_cast<float>(w.y);
          out[2] = static_cast<float>(w.z);
          out[3] = 0.0f;  // the functional attribute (glyph beta), written on the GPU when needed
        }
  };
  const int half = d.z / 2;
  std::thread other(work, 0, half);
  work(half, d.z);
  other.join();
  return g;
}

}  // namespace

VolumeTextures::VolumeTextures(const Volume& volume)
    : dims_(volume.dimensions()), worldFromIndex_(volume.worldFromIndex()) {
  const glm::dvec3 spacing = volume.spacing();
  referenceStepMm_ = volume.smallestSpacing();
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  if (dims_.x > max3d || dims_.y > max3d || dims_.z > max3d)
    throw Error("volume " + std::to_string(dims_.x) + " x " + std::to_string(dims_.y) + " x " +
                std::to_string(dims_.z) + " exceeds the GL's largest 3D texture (" +
                std::to_string(max3d) + ")");
  values_ = valuesOf(volume);
  const auto [lo, hi] = std::minmax_element(values_.begin(), values_.end());
  range_ = {*lo, *hi};
  // Sampling of the intensity (linear or nearest) is set per frame.
  intensity_ = upload3D(dims_, GL_R32F, GL_RED, values_.data(), true, "uploading the volume");
  const std::vector<float> gradient = gradientOf(values_, dims_, spacing, volume.direction());
  gradient_ =
      upload3D(dims_, GL_RGBA16F, GL_RGBA, gradient.data(), true, "uploading the gradient volume");
}

void VolumeTextures::setLinear(bool linear) const {
  setSampling(intensity_.id(), GL_TEXTURE_3D, linear);
}

glm::dmat4 VolumeTextures::textureFromWorld() const {
  return textureFromIndex(dims_) * glm::inverse(worldFromIndex_);
}

std::pair<double, double> VolumeTextures::transferRange() const {
  return {range_.first, range_.second > range_.first ? range_.second : range_.first + 1.0};
}

}  // namespace mvw::render::detail
