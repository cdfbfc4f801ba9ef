#include "VolumeTextures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "TextureUpload.h"
#include "mvw/core/Error.h"

namespace mvw::render::detail {

namespace {

// Slices per upload slab: what the CPU holds at a time while the volume and its gradient go
// to the GL (a few MB for a 512 x 512 CT), instead of whole-volume float copies.
constexpr int kSlabSlices = 16;

// The Sobel gradient of slices k0..k1-1, from `v`: component 0 as float of slices
// first..first+n-1, which holds k0-1..k1 where they exist. Central differences on the voxel
// grid with physical spacing (one-sided at the border), each averaged over the 3 x 3
// neighbours across it with weights 1 2 1, so that 8-bit data shade without contour terraces;
// turned into world (LPS) directions with the direction matrix. The fourth component carries
// the functional attribute for glyph shading (GlyphTextures::updateBeta), 0 here.
void gradientSlab(const std::vector<float>& v, int first, glm::ivec3 d, int k0, int k1,
                  const glm::dvec3& spacing, const glm::dmat3& direction, float* g) {
  auto at = [&](int i, int j, int k) {
    return v[(static_cast<std::size_t>(k - first) * d.y + j) * d.x + i];
  };
  // Away from the border no index clamps: the same sums in the same order (so the same bits)
  // from fixed offsets, about ten times faster than `border`'s clamped form.
  const std::ptrdiff_t stride[3] = {1, d.x, static_cast<std::ptrdiff_t>(d.x) * d.y};
  auto inner = [&](const float* c, int a) {
    const int b = (a + 1) % 3, e = (a + 2) % 3;
    double sum = 0.0;
    for (int db = -1; db <= 1; ++db)
      for (int de = -1; de <= 1; ++de) {
        const float* n = c + db * stride[b] + de * stride[e];
        const double w = (db == 0 ? 2.0 : 1.0) * (de == 0 ? 2.0 : 1.0);
        sum += w * (n[stride[a]] - n[-stride[a]]);
      }
    return sum / 16.0 / (2 * spacing[a]);
  };
  // At the border: the neighbours clamped to the volume, one-sided differences.
  auto border = [&](const glm::ivec3& c) {
    glm::dvec3 local(0.0);
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
    return local;
  };
  auto work = [&](int j0, int j1) {
    for (int k = k0; k < k1; ++k)
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < d.x; ++i) {
          glm::dvec3 local;
          if (i > 0 && i + 1 < d.x && j > 0 && j + 1 < d.y && k > 0 && k + 1 < d.z) {
            const float* c = &v[(static_cast<std::size_t>(k - first) * d.y + j) * d.x + i];
            local = glm::dvec3(inner(c, 0), inner(c, 1), inner(c, 2));
          } else {
            local = border(glm::ivec3(i, j, k));
          }
          const glm::dvec3 w = direction * local;
          float* out = &g[((static_cast<std::size_t>(k - k0) * d.y + j) * d.x + i) * 4];
          out[0] = static_cast<float>(w.x);
          out[1] = static_cast<float>(w.y);
          out[2] = static_cast<float>(w.z);
          out[3] = 0.0f;
        }
  };
  std::thread other(work, 0, d.y / 2);
  work(d.y / 2, d.y);
  other.join();
}

// A bound on every world component of gradientSlab's gradient: its Sobel-averaged central
// differences are weighted means of differences between neighbours along the axis, so no
// local component exceeds the largest neighbour difference over the spacing, and no world
// component exceeds the local vector's length. One cheap pass over component 0 (two threads
// over k), instead of the gradient computed twice.
template <class T>
double gradientBound(const T* p, int nc, glm::ivec3 d, const glm::dvec3& spacing) {
  const std::size_t sx = nc, sy = sx * d.x, sz = sy * d.y;
  auto work = [&](int k0, int k1, glm::dvec3& out) {
    glm::dvec3 m(0.0);
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < d.y; ++j) {
        const T* row = p + k * sz + j * sy;
        for (int i = 0; i < d.x; ++i) {
          const double v = static_cast<double>(row[i * sx]);
          if (i + 1 < d.x) m.x = std::max(m.x, std::abs(double(row[(i + 1) * sx]) - v));
          if (j + 1 < d.y) m.y = std::max(m.y, std::abs(double(row[i * sx + sy]) - v));
          if (k + 1 < d.z) m.z = std::max(m.z, std::abs(double(row[i * sx + sz]) - v));
        }
      }
    out = m;
  };
  glm::dvec3 a, b;
  std::thread other(work, 0, d.z / 2, std::ref(a));
  work(d.z / 2, d.z, b);
  other.join();
  const glm::dvec3 local = glm::max(a, b) / spacing;
  const double bound = std::sqrt(glm::dot(local, local));
  return bound > 0.0 ? bound : 1.0;
}

// How a scalar type goes to the GL: 8- and 16-bit integers exactly as 16-bit normalised texels
// (signed ones shifted to unsigned: the normalised signed formats cannot tell -128 / -32768
// from the next value up), everything else as 32-bit float. Not R8 for 8-bit voxels: llvmpipe
// filters 8-bit texels with 8-bit weights, which moved isosurfaces of the 8-bit ch2better by
// enough to flip glyph edge pixels (up to 169 grey levels on 0.06 % of the atlas golden).
struct Layout {
  GLenum internalFormat, type;
  glm::dvec2 mapping;  // physical = texel (0..1 for normalised formats) * x + y
};

template <class T>
Layout layoutOf() {
  if constexpr (std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::uint16_t>)
    return {GL_R16, GL_UNSIGNED_SHORT, {65535.0, 0.0}};
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return {GL_R16, GL_UNSIGNED_SHORT, {65535.0, -128.0}};
  else if constexpr (std::is_same_v<T, std::int16_t>)
    return {GL_R16, GL_UNSIGNED_SHORT, {65535.0, -32768.0}};
  else
    return {GL_R32F, GL_FLOAT, {1.0, 0.0}};
}

// The texel of one value in the layout above.
template <class T>
auto texelOf(T v) {
  if constexpr (std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::uint16_t>)
    return static_cast<std::uint16_t>(v);
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return static_cast<std::uint16_t>(static_cast<int>(v) + 128);
  else if constexpr (std::is_same_v<T, std::int16_t>)
    return static_cast<std::uint16_t>(static_cast<int>(v) + 32768);
  else
    return static_cast<float>(v);
}

// The largest 3D texture side the renderer uses: the GL's, or MVW_MAX_3D_TEXTURE_SIZE where
// that is smaller (to try folding, and the GL limits of other machines, on this one).
int largestTextureSide() {
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  const char* limit = std::getenv("MVW_MAX_3D_TEXTURE_SIZE");
  if (!limit || !*limit) return max3d;
  char* end = nullptr;
  const long n = std::strtol(limit, &end, 10);
  if (*end != '\0' || n < 4 || n > 1 << 20)
    throw InputError("MVW_MAX_3D_TEXTURE_SIZE", std::string("'") + limit +
                                                    "' is not a whole number of texels from 4 "
                                                    "to 1048576");
  return std::min<int>(max3d, static_cast<int>(n));
}

// The matrix that turns derivatives per mm along the voxel axes (d/di / spacing_i) into the
// world gradient: the direction cosines when the axes are perpendicular; for a sheared grid
// (a gantry tilt kept in the matrix) the inverse transpose of the index-to-world matrix times
// the spacings, since a derivative along one skewed axis also moves along the others. The
// perpendicular case keeps the direction cosines bit for bit.
glm::dmat3 gradientAxes(const Volume& volume) {
  const glm::dmat3 d = volume.direction();
  const double skew = std::max({std::abs(glm::dot(d[0], d[1])), std::abs(glm::dot(d[0], d[2])),
                                std::abs(glm::dot(d[1], d[2]))});
  if (skew < 1e-9) return d;
  const glm::dmat3 linear(volume.worldFromIndex());
  glm::dmat3 spacing(0.0);
  for (int a = 0; a < 3; ++a) spacing[a][a] = volume.spacing()[a];
  return glm::transpose(glm::inverse(linear)) * spacing;
}

}  // namespace

VolumeTextures::VolumeTextures(const Volume& volume, GradientSource gradient)
    : dims_(volume.dimensions()),
      worldFromIndex_(volume.worldFromIndex()),
      spacing_(volume.spacing()),
      direction_(gradientAxes(volume)),
      referenceStepMm_(volume.smallestSpacing()) {
  const int max3d = largestTextureSide();
  // Too large for this GL: bad input for this machine, named by the volume's file.
  const std::filesystem::path name = volume.metadata().sourcePath.empty()
                                         ? std::filesystem::path("the anatomical volume")
                                         : std::filesystem::path(volume.metadata().sourcePath);
  const std::string size = std::to_string(dims_.x) + " x " + std::to_string(dims_.y) + " x " +
                           std::to_string(dims_.z) + " voxels";
  if (dims_.x > max3d || dims_.y > max3d)
    throw InputError(name, size + " exceed the GL's largest 3D texture (" + std::to_string(max3d) +
                               ") across the slices (only the slice axis can be folded)");
  textureDims_ = dims_;
  if (dims_.z > max3d) {
    // Runs of foldSlices_ + 1 slices (neighbours share one), as few as fit.
    foldRuns_ = (dims_.z - 1 + max3d - 2) / (max3d - 1);
    foldSlices_ = (dims_.z - 1 + foldRuns_ - 1) / foldRuns_;
    textureDims_ = {dims_.x * foldRuns_, dims_.y, foldSlices_ + 1};
    if (textureDims_.x > max3d)
      throw InputError(name, size + " exceed the GL's largest 3D texture (" +
                                 std::to_string(max3d) + "): folded into " +
                                 std::to_string(foldRuns_) + " runs of slices it would be " +
                                 std::to_string(textureDims_.x) + " texels wide");
    if (gradient == GradientSource::Texture)
      throw InputError(name, size + ": more slices than the GL's largest 3D texture (" +
                                 std::to_string(max3d) +
                                 "), so the volume is folded, and a folded volume takes its "
                                 "gradient in the shader: use --gradient shader or auto");
  }
  const std::size_t voxels = volume.voxelCount();
  source_ = gradient != GradientSource::Auto ? gradient
            : foldRuns_ > 1 || voxels * kGradientTextureBytesPerVoxel > kGradientTextureBudgetBytes
                ? GradientSource::OnTheFly
                : GradientSource::Texture;
  const int nc = volume.components();
  const std::size_t sliceVoxels = static_cast<std::size_t>(dims_.x) * dims_.y;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  // The intensity, slab by slab: component 0 converted to the layout's texels.
  dispatchScalar(volume.scalarType(), [&](auto t) {
    using T = decltype(t);
    const Layout layout = layoutOf<T>();
    internalFormat_ = layout.internalFormat;
    mapping_ = layout.mapping;
    intensity_ = upload3D(textureDims_, GLint(layout.internalFormat), GL_RED, layout.type, nullptr,
                          true, "uploading the volume");
    using Texel = decltype(texelOf(T{}));
    std::vector<Texel> slab(sliceVoxels * kSlabSlices);
    const T* p = reinterpret_cast<const T*>(volume.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int k0 = 0; k0 < dims_.z; k0 += kSlabSlices) {
      const int n = std::min(kSlabSlices, dims_.z - k0);
      const T* src = p + static_cast<std::size_t>(k0) * sliceVoxels * nc;
      const std::size_t count = sliceVoxels * n;
      if constexpr (std::is_floating_point_v<T>) {
        for (std::size_t i = 0; i < count; ++i) {
          const T v = src[i * nc];
          if (std::isfinite(v)) {
            lo = std::min<double>(lo, v);
            hi = std::max<double>(hi, v);
          }
          slab[i] = texelOf(v);
        }
      } else {
        // Integers: the range in the voxel type, one component apart (the compiler
        // vectorises that loop; per voxel in double it took 0.4 s of a 512 x 512 x 432 CT).
        T mn = std::numeric_limits<T>::max(), mx = std::numeric_limits<T>::lowest();
        auto convert = [&](auto stride) {
          for (std::size_t i = 0; i < count; ++i) {
            const T v = src[i * stride];
            mn = std::min(mn, v);
            mx = std::max(mx, v);
            slab[i] = texelOf(v);
          }
        };
        if (nc == 1)
          convert(std::integral_constant<std::size_t, 1>{});
        else
          convert(static_cast<std::size_t>(nc));
        if (count > 0) {
          lo = std::min<double>(lo, mn);
          hi = std::max<double>(hi, mx);
        }
      }
      if (foldRuns_ == 1)
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, k0, dims_.x, dims_.y, n, GL_RED, layout.type,
                        slab.data());
      else
        for (int k = k0; k < k0 + n; ++k)
          uploadSlice(GL_RED, layout.type, slab.data() + (k - k0) * sliceVoxels, k);
      checkGl("uploading the volume");
    }
    return 0;
  });
  range_ = lo <= hi ? std::pair{lo, hi} : std::pair{0.0, 0.0};

  if (source_ == GradientSource::OnTheFly) return;
  // The gradient, slab by slab from the values of the slab and one slice either side; packed
  // with the intensity's texels where those are 16-bit (the RGBA16 encoding needs the bound
  // first), else RGBA16F.
  packed_ = internalFormat_ == GL_R16;
  gradient_ = upload3D(dims_, packed_ ? GL_RGBA16 : GL_RGBA16F, GL_RGBA,
                       packed_ ? GL_UNSIGNED_SHORT : GL_FLOAT, nullptr, true,
                       "uploading the gradient volume");
  std::vector<float> values(sliceVoxels * (kSlabSlices + 2));
  std::vector<float> g(sliceVoxels * kSlabSlices * 4);
  std::vector<std::uint16_t> packedSlab(packed_ ? g.size() : 0);
  dispatchScalar(volume.scalarType(), [&](auto t) {
    using T = decltype(t);
    const T* p = reinterpret_cast<const T*>(volume.data());
    if (packed_) gradientBound_ = gradientBound(p, nc, dims_, spacing_);
    const double encode = 0.5 / gradientBound_;  // -bound..+bound to 0..1
    for (int k0 = 0; k0 < dims_.z; k0 += kSlabSlices) {
      const int k1 = std::min(k0 + kSlabSlices, dims_.z);
      const int first = std::max(k0 - 1, 0), last = std::min(k1, dims_.z - 1);
      const T* src = p + static_cast<std::size_t>(first) * sliceVoxels * nc;
      const std::size_t count = sliceVoxels * (last - first + 1);
      for (std::size_t i = 0; i < count; ++i) values[i] = static_cast<float>(src[i * nc]);
      gradientSlab(values, first, dims_, k0, k1, spacing_, direction_, g.data());
      if (!packed_) {
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, k0, dims_.x, dims_.y, k1 - k0, GL_RGBA, GL_FLOAT,
                        g.data());
      } else {
        const T* slab = p + static_cast<std::size_t>(k0) * sliceVoxels * nc;
        const std::size_t n = sliceVoxels * (k1 - k0);
        for (std::size_t i = 0; i < n; ++i) {
          for (int c = 0; c < 3; ++c) {
            const double x = std::clamp(g[i * 4 + c] * encode + 0.5, 0.0, 1.0);
            packedSlab[i * 4 + c] = static_cast<std::uint16_t>(std::lround(x * 65535.0));
          }
          packedSlab[i * 4 + 3] = static_cast<std::uint16_t>(texelOf(slab[i * nc]));
        }
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, k0, dims_.x, dims_.y, k1 - k0, GL_RGBA,
                        GL_UNSIGNED_SHORT, packedSlab.data());
      }
      checkGl("uploading the gradient volume");
    }
    return 0;
  });
}

void VolumeTextures::uploadSlice(GLenum format, GLenum type, const void* texels, int k) const {
  for (int b = 0; b < foldRuns_; ++b) {
    const int local = k - b * foldSlices_;
    if (local < 0 || local > foldSlices_) continue;
    // The last run's spare slices repeat the last slice, as clamping to the edge would.
    const int last = k == dims_.z - 1 ? foldSlices_ : local;
    for (int l = local; l <= last; ++l)
      glTexSubImage3D(GL_TEXTURE_3D, 0, b * dims_.x, 0, l, dims_.x, dims_.y, 1, format, type,
                      texels);
  }
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

std::vector<float> VolumeTextures::values() const {
  const std::size_t n = static_cast<std::size_t>(dims_.x) * dims_.y * dims_.z;
  const std::size_t stored =
      static_cast<std::size_t>(textureDims_.x) * textureDims_.y * textureDims_.z;
  std::vector<float> out(n);
  glBindTexture(GL_TEXTURE_3D, intensity_.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  // Row by row: slice k lies in run b at layer k - b * foldSlices_ (unfolded: run 0, layer k).
  auto readAs = [&](auto texel, GLenum type, auto toValue) {
    std::vector<decltype(texel)> raw(stored);
    glGetTexImage(GL_TEXTURE_3D, 0, GL_RED, type, raw.data());
    const std::size_t w = static_cast<std::size_t>(dims_.x);
    for (int k = 0; k < dims_.z; ++k) {
      const int b = foldRuns_ == 1 ? 0 : std::min(k / foldSlices_, foldRuns_ - 1);
      const int layer = k - b * foldSlices_;
      for (int j = 0; j < dims_.y; ++j) {
        const auto* src = raw.data() +
                          (static_cast<std::size_t>(layer) * textureDims_.y + j) * textureDims_.x +
                          static_cast<std::size_t>(b) * w;
        float* dst = out.data() + (static_cast<std::size_t>(k) * dims_.y + j) * w;
        for (std::size_t i = 0; i < w; ++i) dst[i] = toValue(src[i]);
      }
    }
  };
  // Integer texels map back exactly: (texel / max) * max is not exact in float.
  const double offset = mapping_.y;
  if (internalFormat_ == GL_R16)
    readAs(std::uint16_t{}, GL_UNSIGNED_SHORT,
           [offset](std::uint16_t t) { return static_cast<float>(double(t) + offset); });
  else
    readAs(float{}, GL_FLOAT, [](float t) { return t; });
  checkGl("reading the volume back");
  return out;
}

GLuint VolumeTextures::betaTarget() {
  if (!attributeApart()) return gradient_.id();
  if (!attribute_.id())
    attribute_ = upload3D(textureDims_, GL_R16F, GL_RED, GL_FLOAT, nullptr, true,
                          "making the glyph attribute volume");
  return attribute_.id();
}

void VolumeTextures::setUniforms(const ShaderProgram& p) const {
  glUniform2f(p.uniform("uValueMapping"), float(mapping_.x), float(mapping_.y));
  if (packed_)
    glUniform2f(p.uniform("uGradientDecode"), float(2.0 * gradientBound_), float(-gradientBound_));
  if (foldRuns_ > 1) {
    glUniform4f(p.uniform("uFold"), float(foldSlices_), float(foldRuns_ - 1), float(dims_.x),
                float(1.0 / textureDims_.x));
    glUniform1f(p.uniform("uFoldDepth"), float(1.0 / textureDims_.z));
  }
  if (source_ != GradientSource::OnTheFly) return;
  glUniform3f(p.uniform("uTexel"), float(1.0 / dims_.x), float(1.0 / dims_.y),
              float(1.0 / dims_.z));
  // World gradient from the three central differences along i, j, k (texel +- 1).
  glm::dmat3 scale(0.0);
  for (int a = 0; a < 3; ++a) scale[a][a] = 1.0 / (2.0 * spacing_[a]);
  const glm::mat3 gradientFromDelta(direction_ * scale);
  glUniformMatrix3fv(p.uniform("uGradientFromDelta"), 1, GL_FALSE,
                     glm::value_ptr(gradientFromDelta));
}

}  // namespace mvw::render::detail
