#pragma once
// The ray caster's GL programs (internal to mvw_render), compiled on first use and kept: one
// per mode and compile-time variant, so a feature that is off costs nothing in the ray loop.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "RaycastFeatures.h"
#include "mvw/render/ShaderProgram.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render::detail {

// How the volume's textures hold it (VolumeTextures), the same for every program of a
// renderer: the gradient in a texture of its own; packed with the intensity's texels
// (VolumeTextures::packed), so that composite's trilinear samples read value and gradient in
// one fetch; taken from the intensity on the fly (MVW_GRADIENT_ON_THE_FLY); or on the fly from
// a volume whose slices are folded into its texture (VolumeTextures::foldRuns, MVW_FOLDED),
// which never has a gradient texture. Count: how many there are.
enum class VolumeLayout { Gradient, PackedGradient, OnTheFly, FoldedOnTheFly, Count };

// What a program is compiled from: shader paths under shaders/, the defines ("NAME VALUE")
// prepended to both, in that order, and the files pasted before the fragment shader's own
// (the features' includes and a projection's accumulator, each with what it includes).
struct RaycastSource {
  std::string vertex, fragment;
  std::vector<std::string> defines;
  std::vector<std::string> includes;
};

class RaycastPrograms {
 public:
  explicit RaycastPrograms(VolumeLayout layout) : layout_(layout) {}
  // The program for a ray-cast mode (not the shell modes) with the variants `settings` and
  // `fusion` (the functional colour blended in) ask for.
  const ShaderProgram& forMode(RenderMode mode, const RenderSettings& settings, bool fusion);
  // beta.frag.glsl: the functional attribute into the gradient's alpha.
  const ShaderProgram& beta();
  // Whether forMode's program for `mode` draws box.vert.glsl's proxy (BoxProxy.h), 36
  // vertices; otherwise (MPR) a triangle over the viewport, 3 vertices.
  static bool usesBoxProxy(RenderMode mode);

  // The variants `settings` and `fusion` ask for, whatever the mode: each feature's valueFor
  // (RaycastFeatures.h).
  static RaycastVariants variants(const RenderSettings& settings, bool fusion);
  // forMode's program, from the mode, the layout and the variants alone: no setting reaches
  // a define but through a feature, so every() cannot miss one.
  static RaycastSource source(RenderMode mode, VolumeLayout layout,
                              const RaycastVariants& variants);
  // Every distinct program forMode and beta can make: each ray-cast mode under each layout
  // with each combination of the features' values, each program once.
  static std::vector<RaycastSource> every();

 private:
  const ShaderProgram& cached(const std::string& key, const RaycastSource& source);
  VolumeLayout layout_;
  std::map<std::string, ShaderProgram> programs_;
};

}  // namespace mvw::render::detail
