#pragma once
// What glyph shading (Seipel 2007) reads besides the anatomy (internal to mvw_render): the
// glyph map's cell grid and centres, and the functional attribute (beta) resampled into the
// gradient texture's alpha, each derived again only when its inputs change.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "FunctionalTextures.h"
#include "GlObjects.h"
#include "VolumeTextures.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/ShaderProgram.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render::detail {

class GlyphTextures {
 public:
  // The map for `settings`, unless it is the one already uploaded.
  void uploadMap(const GlyphMapSettings& settings);

  // The functional attribute through `window` and `classes`, written into the alpha of the
  // volume's gradient texture with `betaProgram` (beta.frag.glsl) one slice at a time, unless
  // the gradient already holds it. Leaves the default framebuffer bound.
  // `labels` (when not empty) chooses which labels get glyphs, bumps or dimples. With `kinds`
  // (the MVW_GLYPH_KINDS shading) a label or class of kind k is written as 2 k + its size (the
  // size in 0..1; shaders/common/glyphs.glsl reads both back), the classes' kinds from
  // `classKinds` (the last one past its end).
  void updateBeta(VolumeTextures& volume, const FunctionalTextures& functional, glm::vec2 window,
                  int classes, const std::vector<LabelGlyph>& labels,
                  const std::vector<GlyphKind>& classKinds, bool kinds,
                  const ShaderProgram& betaProgram, GLuint vao);

  // The glyph centres' uniform block and the map's scale, for glyphs of diameterMm; the DVR
  // opacity floor per mm turned into one per step of stepMm (the glyphs feature's uniforms,
  // RaycastFeatures.cpp).
  void setUniforms(const ShaderProgram& program, double diameterMm, double minSize,
                   double dvrOpacityPerMm, double stepMm) const;
  // The kinds' shading's way back from the map to world mm, for glyphs of diameterMm.
  void setKindsUniforms(const ShaderProgram& program, double diameterMm) const;

  GLuint cells() const { return cells_.id(); }

 private:
  // Map voxels per mm of glyphs of diameterMm, and the map's orientation.
  glm::mat3 glyphFromWorld(double diameterMm) const;

  Texture cells_, labelTable_;
  Buffer centres_;
  GlyphMapSettings settings_{0, 0, 0.0, 0};
  double radius_ = 0.0;  // map voxels
  // What the gradient texture's alpha holds: the functional attribute through this mapping.
  struct BetaKey {
    std::uint64_t generation;
    float low, high;
    int classes;
    std::vector<float> labels;
    std::vector<int> classKinds;
    bool operator==(const BetaKey&) const = default;
  };
  std::optional<BetaKey> betaKey_;
};

}  // namespace mvw::render::detail
