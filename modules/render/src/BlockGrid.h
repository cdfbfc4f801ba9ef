#pragma once
// Empty-space skipping for the ray caster (internal to mvw_render): the volume's min/max per
// 8^3 block, and per frame which blocks the transfer function makes visible, so composite rays
// step over blocks that would add nothing.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "GlObjects.h"
#include "mvw/core/Volume.h"

namespace mvw::render::detail {

class BlockGrid {
 public:
  static constexpr int kBlockVoxels = 8;

  // Of the volume's component 0, NaN ("no data") left out. The context must be current.
  explicit BlockGrid(const Volume& volume);

  // Marks the blocks whose value range meets a non-transparent entry of `lut` (sampled over
  // lo..hi); with `skipEmpty` false (modes that see every sample) all blocks are visible.
  void updateVisibility(const std::vector<glm::vec4>& lut, double lo, double hi, bool skipEmpty);

  GLuint visibility() const { return visibility_.id(); }
  GLuint minMax() const { return minMaxTexture_.id(); }

 private:
  glm::ivec3 count_;
  std::vector<glm::vec2> minMax_;
  Texture visibility_, minMaxTexture_;
};

}  // namespace mvw::render::detail
