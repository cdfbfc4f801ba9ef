#pragma once
// The ray caster's GL programs (internal to mvw_render), compiled on first use and kept: one
// per mode and compile-time variant, so a feature that is off costs nothing in the ray loop.
#include <map>
#include <string>
#include <vector>

#include "mvw/render/ShaderProgram.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render::detail {

class RaycastPrograms {
 public:
  // gradientOnTheFly: composite and isosurface take the gradient from the intensity
  // (MVW_GRADIENT_ON_THE_FLY) instead of the gradient texture; packedGradient: the texture
  // holds the intensity too (VolumeTextures::packed), and composite's trilinear samples read
  // value and gradient in one fetch; folded: the volume's slices are folded into its texture
  // (VolumeTextures::foldRuns, MVW_FOLDED).
  RaycastPrograms(bool gradientOnTheFly, bool packedGradient, bool folded)
      : gradientOnTheFly_(gradientOnTheFly), packedGradient_(packedGradient), folded_(folded) {}
  // The program for a ray-cast mode (not the shell modes) with the variants `settings` and
  // `fusion` (the functional colour blended in) ask for.
  const ShaderProgram& forMode(RenderMode mode, const RenderSettings& settings, bool fusion);
  // beta.frag.glsl: the functional attribute into the gradient's alpha.
  const ShaderProgram& beta();
  // Whether forMode's program for `mode` draws box.vert.glsl's proxy (BoxProxy.h), 36
  // vertices; otherwise (MPR) a triangle over the viewport, 3 vertices.
  static bool usesBoxProxy(RenderMode mode);

 private:
  const ShaderProgram& cached(const std::string& key, const std::string& vertex,
                              const std::string& fragment, const std::vector<std::string>& defines);
  bool gradientOnTheFly_;
  bool packedGradient_;
  bool folded_;
  std::map<std::string, ShaderProgram> programs_;
};

}  // namespace mvw::render::detail
