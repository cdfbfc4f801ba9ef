#include "BlockGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>

#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vector_relational.hpp>

#include "TextureUpload.h"
#include "TransferTable.h"

namespace mvw::render::detail {

namespace {

// work(first, end) over the block slices 0 .. slices, on two threads.
template <typename Work>
void onTwoThreads(int slices, const Work& work) {
  std::thread other(work, 0, slices / 2);
  work(slices / 2, slices);
  other.join();
}

// A 3D texture of one texel per block, read with texelFetch (nearest).
void uploadBlocks(GLuint texture, glm::ivec3 count, GLint internalFormat, GLenum format,
                  GLenum type, const void* data) {
  glBindTexture(GL_TEXTURE_3D, texture);
  glTexImage3D(GL_TEXTURE_3D, 0, internalFormat, count.x, count.y, count.z, 0, format, type, data);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

}  // namespace

BlockGrid::BlockGrid(const Volume& volume) {
  constexpr int kB = kBlockVoxels;
  const glm::ivec3 dims = volume.dimensions();
  dims_ = dims;
  const int nc = volume.components();
  count_ = (dims + kB - 1) / kB;
  // Min/max per block, widened by one voxel: trilinear samples near a block's face read the
  // neighbour's voxels too. Block by block over its voxels and the apron (about 1.4 reads a
  // voxel), on two threads split along the block rows; NaN fails both comparisons.
  minMax_.assign(static_cast<std::size_t>(count_.x) * count_.y * count_.z,
                 glm::vec2(3.4e38f, -3.4e38f));
  dispatchScalar(volume.scalarType(), [&](auto t) {
    using T = decltype(t);
    const T* p = reinterpret_cast<const T*>(volume.data());
    auto work = [&](int bk0, int bk1) {
      for (int bk = bk0; bk < bk1; ++bk)
        for (int bj = 0; bj < count_.y; ++bj)
          for (int bi = 0; bi < count_.x; ++bi) {
            const glm::ivec3 b(bi, bj, bk);
            const glm::ivec3 lo = glm::max(b * kB - 1, glm::ivec3(0));
            const glm::ivec3 hi = glm::min(b * kB + kB, dims - 1);
            float mn = 3.4e38f, mx = -3.4e38f;
            for (int k = lo.z; k <= hi.z; ++k)
              for (int j = lo.y; j <= hi.y; ++j) {
                const T* row = p + ((static_cast<std::size_t>(k) * dims.y + j) * dims.x) * nc;
                for (int i = lo.x; i <= hi.x; ++i) {
                  const auto v = static_cast<float>(row[static_cast<std::size_t>(i) * nc]);
                  mn = v < mn ? v : mn;
                  mx = v > mx ? v : mx;
                }
              }
            minMax_[(static_cast<std::size_t>(bk) * count_.y + bj) * count_.x + bi] = {mn, mx};
          }
    };
    onTwoThreads(count_.z, work);
    return 0;
  });
  visibility_ = makeTexture();
  minMaxTexture_ = makeTexture();
  uploadBlocks(minMaxTexture_.id(), count_, GL_RG32F, GL_RG, GL_FLOAT, minMax_.data());
  checkGl("uploading the block grid");
}

void BlockGrid::setFunctional(const Volume& functional,
                              const glm::dmat4& functionalIndexFromIndex) {
  constexpr int kB = kBlockVoxels;
  const glm::ivec3 fd = functional.dimensions();
  const std::vector<float> values = valuesOf(functional);
  const glm::dmat3 linear(functionalIndexFromIndex);
  glm::dmat3 spread;  // |linear|: a box's half extent in the functional's index space
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) spread[c][r] = std::abs(linear[c][r]);
  std::vector<glm::vec4> fused(minMax_.size());
  auto work = [&](int bk0, int bk1) {
    for (int bk = bk0; bk < bk1; ++bk)
      for (int bj = 0; bj < count_.y; ++bj)
        for (int bi = 0; bi < count_.x; ++bi) {
          // A sample in block b sits (as blockOf maps it, clamped to the grid) in continuous
          // index coordinates b kB - 0.5 .. b kB + kB - 0.5, within the box's -0.5 .. dims - 0.5;
          // a hundredth of a voxel more either side, in both grids, for the shader's rounding
          // (its functional position comes from another product than its block).
          const glm::ivec3 b(bi, bj, bk);
          const glm::dvec3 lo = glm::dvec3(b * kB) - 0.51;
          const glm::dvec3 hi = glm::min(glm::dvec3(b * kB + kB), glm::dvec3(dims_)) - 0.49;
          const glm::dvec3 centre =
              glm::dvec3(functionalIndexFromIndex * glm::dvec4(0.5 * (lo + hi), 1.0));
          const glm::dvec3 half = spread * (0.5 * (hi - lo)) + 0.01;
          const glm::dvec3 flo = centre - half, fhi = centre + half;
          float mn = 3.4e38f, mx = -3.4e38f;
          // The functional sample counts only inside its box (-0.5 .. fd - 0.5); trilinear
          // filtering there reads the voxels floor(p) and floor(p) + 1, clamped to the edge.
          if (glm::all(glm::greaterThanEqual(fhi, glm::dvec3(-0.5))) &&
              glm::all(glm::lessThanEqual(flo, glm::dvec3(fd) - 0.5))) {
            const glm::ivec3 i0 = glm::max(glm::ivec3(glm::floor(flo)), glm::ivec3(0));
            const glm::ivec3 i1 = glm::min(glm::ivec3(glm::floor(fhi)) + 1, fd - 1);
            for (int k = i0.z; k <= i1.z; ++k)
              for (int j = i0.y; j <= i1.y; ++j)
                for (int i = i0.x; i <= i1.x; ++i) {
                  const float v = values[(static_cast<std::size_t>(k) * fd.y + j) * fd.x + i];
                  mn = v < mn ? v : mn;
                  mx = v > mx ? v : mx;
                }
            // Widened by a hundred-thousandth: a filtered sample may round past its voxels.
            if (mn <= mx) {
              mn -= 1e-5f * std::abs(mn) + 1e-30f;
              mx += 1e-5f * std::abs(mx) + 1e-30f;
            }
          }
          const std::size_t at = (static_cast<std::size_t>(bk) * count_.y + bj) * count_.x + bi;
          fused[at] = glm::vec4(minMax_[at], mn, mx);
        }
  };
  onTwoThreads(count_.z, work);
  if (!fusedTexture_.id()) fusedTexture_ = makeTexture();
  uploadBlocks(fusedTexture_.id(), count_, GL_RGBA32F, GL_RGBA, GL_FLOAT, fused.data());
  checkGl("uploading the fused block grid");
}

namespace {

// One pass of the Chebyshev (L-infinity) distance transform along one axis of the block grid:
// out(x) = min over x' of max(|x - x'|, in(x')), scanning outward from x until no nearer x'
// can win. Three passes, one per axis, give the distance to the nearest visible block.
void chebyshevPass(std::vector<std::uint8_t>& d, glm::ivec3 count, int axis) {
  const glm::ivec3 stride(1, count.x, count.x * count.y);
  const int n = count[axis];
  glm::ivec3 lines = count;
  lines[axis] = 1;
  std::vector<std::uint8_t> in(static_cast<std::size_t>(n));
  for (int c = 0; c < lines.z; ++c)
    for (int b = 0; b < lines.y; ++b)
      for (int a = 0; a < lines.x; ++a) {
        const std::size_t base = static_cast<std::size_t>(a) * stride.x +
                                 static_cast<std::size_t>(b) * stride.y +
                                 static_cast<std::size_t>(c) * stride.z;
        for (int x = 0; x < n; ++x) in[x] = d[base + static_cast<std::size_t>(x) * stride[axis]];
        for (int x = 0; x < n; ++x) {
          int best = in[x];
          for (int r = 1; r < best; ++r) {
            if (x - r >= 0) best = std::min(best, std::max(r, int(in[x - r])));
            if (x + r < n) best = std::min(best, std::max(r, int(in[x + r])));
            if (x - r < 0 && x + r >= n) break;
          }
          d[base + static_cast<std::size_t>(x) * stride[axis]] = static_cast<std::uint8_t>(best);
        }
      }
}

}  // namespace

void BlockGrid::updateVisibility(const std::vector<glm::vec4>& lut, double lo, double hi,
                                 bool skipEmpty) {
  // 0 where a block is visible, else its Chebyshev distance (in blocks, at most 255) to the
  // nearest visible one: every block nearer than that is empty, so a ray skips the whole cube.
  if (skipEmpty_ == int(skipEmpty) && lo == lo_ && hi == hi_ && (!skipEmpty || lut == lut_)) return;
  skipEmpty_ = int(skipEmpty);
  lo_ = lo;
  hi_ = hi;
  lut_ = lut;
  std::vector<std::uint8_t> distance(minMax_.size(), 0);
  if (skipEmpty) {
    // The entries linear filtering reads for values in the block's range (where the shader
    // looks a value up: TransferTable::entryOf), widened by a hundredth of an entry for the
    // shader's float rounding.
    const int n = static_cast<int>(lut.size());
    for (std::size_t b = 0; b < distance.size(); ++b) {
      const auto e0 =
          static_cast<int>(std::floor(TransferTable::entryOf(minMax_[b].x, lo, hi) - 0.01));
      const auto e1 =
          static_cast<int>(std::ceil(TransferTable::entryOf(minMax_[b].y, lo, hi) + 0.01));
      bool any = false;
      for (int e = std::max(0, e0); e <= std::min(n - 1, e1) && !any; ++e) any = lut[e].a > 0.0f;
      distance[b] = any ? 0 : 255;
    }
    for (int axis = 0; axis < 3; ++axis) chebyshevPass(distance, count_, axis);
  }
  // The visible blocks' box, as the shader's blockOf maps texture coordinates to blocks (the
  // grid's first and last blocks reach on to the box's faces).
  glm::ivec3 first = count_, last(-1);
  for (int bk = 0, b = 0; bk < count_.z; ++bk)
    for (int bj = 0; bj < count_.y; ++bj)
      for (int bi = 0; bi < count_.x; ++bi, ++b)
        if (distance[b] == 0) {
          first = glm::min(first, glm::ivec3(bi, bj, bk));
          last = glm::max(last, glm::ivec3(bi, bj, bk));
        }
  if (last.x < 0) {
    visibleBox_ = {glm::dvec3(1.0), glm::dvec3(0.0)};
  } else {
    const glm::dvec3 size = glm::dvec3(kBlockVoxels) / glm::dvec3(dims_);
    visibleBox_.first =
        glm::mix(glm::dvec3(first) * size, glm::dvec3(0.0), glm::equal(first, glm::ivec3(0)));
    visibleBox_.second =
        glm::mix(glm::dvec3(last + 1) * size, glm::dvec3(1.0), glm::equal(last, count_ - 1));
  }
  uploadBlocks(visibility_.id(), count_, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
               distance.data());
}

}  // namespace mvw::render::detail
