#pragma once
// The anatomical volume on the GPU (internal to mvw_render): its values as an R32F texture and
// its gradient as RGBA16F, plus the geometry the ray caster needs to sample them in world space.
// The gradient's alpha is free for the functional attribute (GlyphTextures writes it).
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "GlObjects.h"
#include "mvw/core/Volume.h"

namespace mvw::render::detail {

class VolumeTextures {
 public:
  // The context must be current. Throws mvw::Error if the GL cannot hold the volume.
  explicit VolumeTextures(const Volume& volume);

  // Trilinear or nearest sampling of the intensity; the gradient is always trilinear.
  void setLinear(bool linear) const;

  glm::ivec3 dims() const { return dims_; }
  const glm::dmat4& worldFromIndex() const { return worldFromIndex_; }
  glm::dmat4 textureFromWorld() const;
  // The smallest voxel spacing (mm): the step the transfer function's opacities refer to.
  double referenceStepMm() const { return referenceStepMm_; }
  std::pair<double, double> range() const { return range_; }
  // The range the transfer table spans: the value range, one unit wide when it is flat.
  std::pair<double, double> transferRange() const;
  // Component 0 as float, kept for what is computed on the CPU (block grid, shells).
  const std::vector<float>& values() const { return values_; }
  GLuint intensity() const { return intensity_.id(); }
  GLuint gradient() const { return gradient_.id(); }

 private:
  glm::ivec3 dims_;
  glm::dmat4 worldFromIndex_;
  double referenceStepMm_;
  std::vector<float> values_;
  std::pair<double, double> range_;
  Texture intensity_, gradient_;
};

}  // namespace mvw::render::detail
