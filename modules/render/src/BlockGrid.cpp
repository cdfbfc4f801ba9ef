#include "BlockGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "TextureUpload.h"

namespace mvw::render::detail {

BlockGrid::BlockGrid(const std::vector<float>& values, glm::ivec3 dims) {
  constexpr int kB = kBlockVoxels;
  count_ = (dims + kB - 1) / kB;
  // Min/max per block, widened by one voxel: trilinear samples near a block's face read the
  // neighbour's voxels too.
  minMax_.assign(static_cast<std::size_t>(count_.x) * count_.y * count_.z,
                 glm::vec2(3.4e38f, -3.4e38f));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const float v = values[(static_cast<std::size_t>(k) * dims.y + j) * dims.x + i];
        for (int bk = std::max(0, (k - 1) / kB); bk <= std::min(count_.z - 1, (k + 1) / kB); ++bk)
          for (int bj = std::max(0, (j - 1) / kB); bj <= std::min(count_.y - 1, (j + 1) / kB); ++bj)
            for (int bi = std::max(0, (i - 1) / kB); bi <= std::min(count_.x - 1, (i + 1) / kB);
                 ++bi) {
              glm::vec2& b =
                  minMax_[(static_cast<std::size_t>(bk) * count_.y + bj) * count_.x + bi];
              b.x = std::min(b.x, v);
              b.y = std::max(b.y, v);
            }
      }
  visibility_ = makeTexture();
  minMaxTexture_ = makeTexture();
  glBindTexture(GL_TEXTURE_3D, minMaxTexture_.id());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RG32F, count_.x, count_.y, count_.z, 0, GL_RG, GL_FLOAT,
               minMax_.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  checkGl("uploading the block grid");
}

void BlockGrid::updateVisibility(const std::vector<glm::vec4>& lut, double lo, double hi,
                                 bool skipEmpty) {
  std::vector<std::uint8_t> visible(minMax_.size(), 1);
  if (skipEmpty) {
    const int n = static_cast<int>(lut.size());
    for (std::size_t b = 0; b < visible.size(); ++b) {
      const auto e0 = static_cast<int>(std::floor((minMax_[b].x - lo) / (hi - lo) * (n - 1)));
      const auto e1 = static_cast<int>(std::ceil((minMax_[b].y - lo) / (hi - lo) * (n - 1)));
      bool any = false;
      for (int e = std::max(0, e0); e <= std::min(n - 1, e1) && !any; ++e) any = lut[e].a > 0.0f;
      visible[b] = any;
    }
  }
  glBindTexture(GL_TEXTURE_3D, visibility_.id());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R8UI, count_.x, count_.y, count_.z, 0, GL_RED_INTEGER,
               GL_UNSIGNED_BYTE, visible.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

}  // namespace mvw::render::detail
