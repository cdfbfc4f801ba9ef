#pragma once
// Empty-space skipping for the ray caster (internal to mvw_render): the volume's min/max per
// 6^3 block, and per frame which blocks the transfer function makes visible, so composite rays
// step over blocks that would add nothing: over every block within the distance to the
// nearest visible one at once. 6 voxels: on the Cranium CT composite took 62 ms/frame with
// 4^3 and 6^3 blocks, 67 with 8^3, 145 with 2^3 (docs/performance-log.md#block-size).
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "GlObjects.h"
#include "mvw/core/Volume.h"

namespace mvw::render::detail {

// The Chebyshev (chessboard) distance in blocks of every block of a grid of `count` blocks (x
// fastest) to the nearest 0 in `d` (0: visible, 255: not), at most 255, in place:
// BlockGrid::updateVisibility's map, here for its test.
void chessboardDistance(std::vector<std::uint8_t>& d, glm::ivec3 count);

// The Chebyshev distance in blocks of every block of `minMax` (per block min, max; a grid of
// `count` blocks, x fastest) to the nearest block whose maximum is at or above `level`: 0 for
// those blocks themselves, at most 255. Every block nearer than that has its maximum under
// `level`: BlockGrid::prepareMipLevels's maps, here for its test.
std::vector<std::uint8_t> distanceToMaximumAtLeast(const std::vector<glm::vec2>& minMax,
                                                   glm::ivec3 count, float level);

class BlockGrid {
 public:
  static constexpr int kBlockVoxels = 6;

  // Of the volume's component 0, NaN ("no data") left out. The context must be current.
  explicit BlockGrid(const Volume& volume);

  // Marks the blocks whose value range meets a non-transparent entry of `lut` (the
  // TransferTable's, sampled over lo..hi) with 0, every other with its Chebyshev distance in blocks
  // to the nearest of those (at most 255); with `skipEmpty` false (modes that see every sample) all
  // blocks are 0.
  void updateVisibility(const std::vector<glm::vec4>& lut, double lo, double hi, bool skipEmpty);

  // The box, in texture coordinates (0..1 across the voxel box), that holds every block
  // updateVisibility marked visible: no sample outside it can show. Empty (min > max) where
  // none is; the whole box with skipEmpty false.
  std::pair<glm::dvec3, glm::dvec3> visibleBox() const { return visibleBox_; }

  // The fused projections' grid (issue 53): per block of this grid, the anatomy's min/max
  // (RG, as minMax) and the functional volume's (BA) over every point a sample in the block
  // can read it at, through functionalIndexFromIndex (this volume's voxel index -> the
  // functional's, affine: the registration); +3.4e38 / -3.4e38 where no sample in the block
  // lies inside the functional volume. A fused ray then skips a block only where neither
  // volume can change its projection. Context current.
  void setFunctional(const Volume& functional, const glm::dmat4& functionalIndexFromIndex);

  // MIP's skip over several settled blocks at once (issue 53): kMipLevels rising levels of the
  // block maxima (those that a half, a quarter and a tenth of the blocks reach; +3.4e38 where
  // no block holds data), and per block, for each level, distanceToMaximumAtLeast: a ray whose
  // pre-pass bound is at or above a level steps over every block nearer than that distance at
  // once (raycast/accumulate-mip.glsl). Made on the first MIP frame (about 8 MB of texture on
  // the 512 x 512 x 432 CT), not for other modes. Context current.
  static constexpr int kMipLevels = 3;
  void prepareMipLevels();
  // The levels, +3.4e38 each before prepareMipLevels.
  glm::vec3 mipLevels() const { return mipLevels_; }

  GLuint visibility() const { return visibility_.id(); }
  GLuint minMax() const { return minMaxTexture_.id(); }
  // RGBA32F: the block's maximum and the three levels' distances; 0 before prepareMipLevels.
  GLuint mipRange() const { return mipTexture_.id(); }
  // RGBA32F; 0 before setFunctional.
  GLuint fusedMinMax() const { return fusedTexture_.id(); }

 private:
  glm::ivec3 dims_, count_;
  std::pair<glm::dvec3, glm::dvec3> visibleBox_{glm::dvec3(0.0), glm::dvec3(1.0)};
  std::vector<glm::vec2> minMax_;
  // What the uploaded distances were computed for: the viewer asks every frame.
  std::vector<glm::vec4> lut_;
  double lo_ = 0.0, hi_ = 0.0;
  int skipEmpty_ = -1;
  glm::vec3 mipLevels_{3.4e38f};
  Texture visibility_, minMaxTexture_, fusedTexture_, mipTexture_;
};

}  // namespace mvw::render::detail
