#pragma once
// Segment masks on the GPU (internal to mvw_render) for outlines on MPR views: one bit per
// segment in an unsigned integer 3D texture on the segmentation's own grid, placed by a
// transform into the anatomical world; shaders read it through common/segments.glsl.
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "GlObjects.h"
#include "mvw/core/Volume.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render::detail {

class SegmentTextures {
 public:
  static constexpr int kMaxSegments = 16;

  // masks: one component per segment, non-zero inside (the first kMaxSegments are drawn);
  // colours: one per component (sRGB 0..1). Context current.
  void set(const Volume& masks, const std::vector<glm::vec3>& colours,
           const glm::dmat4& anatomicalFromSegmentation);
  bool present() const { return texture_.id() != 0; }
  // uSegmentsFromWorld, uSegmentDims, uSegmentCount (0 when `show` is false), uSegmentColours.
  void setUniforms(const ShaderProgram& program, bool show) const;
  GLuint texture() const { return texture_.id(); }

 private:
  Texture texture_;
  glm::ivec3 dims_{0};
  int count_ = 0;
  std::vector<glm::vec3> colours_;
  glm::dmat4 indexFromAnatomicalWorld_{1.0};
};

}  // namespace mvw::render::detail
