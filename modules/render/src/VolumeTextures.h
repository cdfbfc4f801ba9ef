#pragma once
// The anatomical volume on the GPU (internal to mvw_render): its values in the narrowest
// texture that holds them exactly (R16 for 8- and 16-bit voxels, R32F otherwise) with a
// value mapping back to the physical unit, and its gradient, either precomputed (RGBA16F) or
// taken by the shaders from the intensity (GradientSource), plus the geometry the ray caster
// needs to sample them in world space. Nothing of the volume stays on the CPU: what is
// computed there (the shells' meshes) reads the texture back.
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "GlObjects.h"
#include "mvw/core/Volume.h"
#include "mvw/render/ShaderProgram.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render::detail {

class VolumeTextures {
 public:
  // The context must be current. Throws mvw::Error if the GL cannot hold the volume.
  VolumeTextures(const Volume& volume, GradientSource gradient);

  // Trilinear or nearest sampling of the intensity; the gradient is always trilinear.
  void setLinear(bool linear) const;

  glm::ivec3 dims() const { return dims_; }
  // Folding: a volume with more slices than the GL's largest 3D texture
  // (GL_MAX_3D_TEXTURE_SIZE, or MVW_MAX_3D_TEXTURE_SIZE where that is smaller) is stored as
  // foldRuns() runs of foldSlices() + 1 slices side by side along x in one texture of
  // textureDims(); neighbouring runs share a slice, so trilinear sampling within a run reads
  // exactly the voxels it would unfolded. The shaders (MVW_FOLDED, common.glsl storedTexture)
  // map the volume's texture coordinates into it; its gradient is then always taken on the fly.
  int foldRuns() const { return foldRuns_; }
  int foldSlices() const { return foldSlices_; }
  glm::ivec3 textureDims() const { return textureDims_; }
  const glm::dmat4& worldFromIndex() const { return worldFromIndex_; }
  glm::dmat4 textureFromWorld() const;
  // The smallest voxel spacing (mm): the step the transfer function's opacities refer to.
  double referenceStepMm() const { return referenceStepMm_; }
  // Of component 0, finite values only.
  std::pair<double, double> range() const { return range_; }
  // The range the transfer table spans: the value range, one unit wide when it is flat.
  std::pair<double, double> transferRange() const;
  // Component 0 as float in the physical unit, read back from the GL (exactly the values
  // uploaded): for what is computed on the CPU on demand (the shells' meshes).
  std::vector<float> values() const;
  GLuint intensity() const { return intensity_.id(); }
  // The precomputed gradient, 0 with the gradient taken on the fly. For 8- and 16-bit values
  // (the R16 intensity) packed: RGBA16, the gradient in RGB (gradientDecode) and the
  // intensity's texel in A; otherwise RGBA16F, the gradient in RGB and the glyph attribute in A.
  GLuint gradient() const { return gradient_.id(); }
  bool packed() const { return packed_; }
  // The glyph attribute's own R16F volume where the gradient's A does not hold it (packed, or
  // on the fly), made by betaTarget; 0 otherwise or before.
  GLuint attribute() const { return attribute_.id(); }
  // The texture glyph shading's attribute is written into (GlyphTextures::updateBeta), made
  // when first asked for; the colour channel it takes it in (3: alpha, 0: red).
  GLuint betaTarget();
  int betaChannel() const { return attributeApart() ? 0 : 3; }
  // Texture or OnTheFly (never Auto): what the shaders are compiled for.
  GradientSource gradientSource() const { return source_; }
  // uValueMapping (texel to physical unit) and what the gradient needs (on the fly, packed).
  void setUniforms(const ShaderProgram& p) const;

 private:
  glm::ivec3 dims_;
  int foldRuns_ = 1, foldSlices_ = 0;
  glm::ivec3 textureDims_;
  // Uploads slice k (w x h texels of `type`) wherever the folded layout holds it.
  void uploadSlice(GLenum format, GLenum type, const void* texels, int k) const;
  glm::dmat4 worldFromIndex_;
  glm::dvec3 spacing_;
  glm::dmat3 direction_;  // gradient axes: see gradientAxes (the direction cosines unless sheared)
  double referenceStepMm_;
  std::pair<double, double> range_;
  GLenum internalFormat_ = 0;
  glm::dvec2 mapping_{1.0, 0.0};  // physical = texel * x + y
  bool attributeApart() const { return source_ == GradientSource::OnTheFly || packed_; }
  GradientSource source_;
  bool packed_ = false;
  double gradientBound_ = 1.0;  // packed: the gradient texel's 0..1 spans -bound..+bound
  Texture intensity_, gradient_, attribute_;
};

}  // namespace mvw::render::detail
