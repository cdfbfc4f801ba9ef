#include "RaycastFeatures.h"

#include <algorithm>

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "GlyphTextures.h"
#include "TransferTable.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/render/GlyphMap.h"

namespace mvw::render::detail {

namespace {

bool onlyMip(RenderMode m) { return m == RenderMode::Mip; }
bool onlyComposite(RenderMode m) { return m == RenderMode::Composite; }
// Composite colours the anatomy where it samples it; the projections lay the functional
// volume's own projection over theirs (isosurface and MPR blend it by a uniform instead).
bool fusedModes(RenderMode m) { return m == RenderMode::Composite || isProjectionMode(m); }
bool shadedModes(RenderMode m) { return hasCutFace(m); }  // composite and isosurface

// Chosen labels carry their own kind (bump or dimple) through the "both" shading; other kinds
// (issue 40) take the kinds' shading, each glyph's kind read at its foot.
GlyphShading glyphShadingOf(const RenderSettings& s) {
  if (usesGlyphKinds(s)) return GlyphShading::Kinds;
  if (s.glyphs.convexity == GlyphConvexity::Both || !s.glyphLabels.empty())
    return GlyphShading::Both;
  return s.glyphs.convexity == GlyphConvexity::Dimples ? GlyphShading::Dimples
                                                       : GlyphShading::Bumps;
}

constexpr RaycastFeature kNone = RaycastFeature::Count;

std::vector<const char*> fusionIncludes(RenderMode m) {
  if (isProjectionMode(m)) return {"raycast/fusion-projection.glsl"};
  return {};  // composite: common/functional.glsl's fuseColour, which it includes itself
}
std::vector<const char*> glyphIncludes(RenderMode) { return {"common/glyphs.glsl"}; }
std::vector<const char*> cutFaceIncludes(RenderMode) { return {"raycast/cutface.glsl"}; }

// Depth cue: the ramp (beta0, a, b) over the framing sphere's depth.
void setDepthCueUniforms(const ShaderProgram& p, const FeatureFrame& f) {
  const DepthCue& cue = f.settings.depthCue;
  glUniform3f(p.uniform("uCue"), float(cue.brightness), float(cue.amount), float(cue.contrast));
  const glm::dvec3& c = f.framing.centre;
  glUniform4f(p.uniform("uBoundingSphere"), float(c.x), float(c.y), float(c.z),
              float(f.framing.radius));
}

// The 2D transfer function's rows over the gradient magnitude.
void setTf2dUniforms(const ShaderProgram& p, const FeatureFrame& f) {
  glUniform1f(p.uniform("uGradientScale"), float(f.transfer.gradientScale()));
  const double rows = f.transfer.rows();
  glUniform2f(p.uniform("uGradientRows"), float((rows - 1.0) / rows), float(0.5 / rows));
}

// The glyph map's scale and centres; the DVR opacity floor per step.
void setGlyphUniforms(const ShaderProgram& p, const FeatureFrame& f) {
  const RenderSettings& s = f.settings;
  f.glyphs.setUniforms(p, s.glyphDiameterMm, s.glyphs.minSize, s.glyphs.dvrOpacity, f.stepMm);
}

// The kinds' shading: glyph space back to world mm, the surface layer, and glyphs on the
// visible surface laid out in the image.
void setGlyphKindsUniforms(const ShaderProgram& p, const FeatureFrame& f) {
  const RenderSettings& s = f.settings;
  const Camera& camera = f.camera;
  f.glyphs.setKindsUniforms(p, s.glyphDiameterMm);
  glUniform1f(p.uniform("uGlyphLayerMm"), float(std::max(s.glyphLayerMm, 0.0)));
  // Glyphs on the visible surface: the glyph's radius in pixels (0: the 3D lattice).
  const bool onSurface = s.glyphs.onSurface && !camera.perspective && camera.halfHeightMm > 0;
  const double radiusPx = 0.5 * s.glyphDiameterMm * s.size.y / (2.0 * camera.halfHeightMm);
  glUniform1f(p.uniform("uGlyphScreenRadiusPx"), onSurface ? float(radiusPx) : 0.0f);
  glUniform1f(p.uniform("uGlyphScreenSpacingPx"),
              float(2.0 * radiusPx / kBlueNoiseDiameterFraction));
  glUniform3fv(p.uniform("uGlyphScreenRight"), 1, glm::value_ptr(glm::vec3(camera.right)));
  glUniform3fv(p.uniform("uGlyphScreenUp"), 1, glm::value_ptr(glm::vec3(camera.up)));
}

}  // namespace

const std::array<RaycastFeatureSpec, kRaycastFeatureCount>& raycastFeatures() {
  using F = RaycastFeature;
  static const std::array<RaycastFeatureSpec, kRaycastFeatureCount> table{{
      // Heidrich, McCool and Stevens' depth-cued MIP (raycast/accumulate-mip.glsl).
      {.id = F::DepthCue,
       .name = "depth cue",
       .values = 2,
       .defines = {nullptr, "MVW_DEPTH_CUE 1"},
       .includes = nullptr,
       .uniforms = {"uCue", "uBoundingSphere"},
       .setUniforms = setDepthCueUniforms,
       .appliesTo = onlyMip,
       .needs = kNone,
       .valueFor = [](const RenderSettings& s, bool) { return int(s.depthCue.on); }},
      // Nearest-neighbour samples: MIP drops its pre-pass (accumulate-mip.glsl); composite with
      // the packed gradient reads the value from the intensity, not the always trilinear packed
      // texture (RaycastPrograms::source's layout defines). The texture's filter:
      // VolumeTextures::setLinear.
      {.id = F::Nearest,
       .name = "nearest",
       .values = 2,
       .defines = {nullptr, "MVW_NEAREST 1"},
       .includes = nullptr,
       .uniforms = {},
       .appliesTo = onlyMip,
       .needs = kNone,
       .valueFor = [](const RenderSettings& s, bool) { return int(!s.linear); }},
      // Composite's 2D transfer function over value and gradient magnitude.
      {.id = F::Tf2d,
       .name = "2D transfer function",
       .values = 2,
       .defines = {nullptr, "MVW_TF2D 1"},
       .includes = nullptr,
       .uniforms = {"uGradientScale", "uGradientRows"},
       .setUniforms = setTf2dUniforms,
       .appliesTo = onlyComposite,
       .needs = kNone,
       .valueFor = [](const RenderSettings& s, bool) { return int(s.gradientOpacity.on()); }},
      // Colour fusion: composite blends the functional colour in per sample (common/
      // functional.glsl); a fused projection lays the functional volume's own projection over
      // the anatomy's (raycast/fusion-projection.glsl, with the fused block grid).
      {.id = F::Fusion,
       .name = "fusion",
       .values = 2,
       .defines = {nullptr, "MVW_FUSION 1"},
       .includes = fusionIncludes,
       .uniforms = {},
       .sharedUniforms = {"uFunctionalFromWorld", "uColormap", "uOverlayOpacity",
                          "uOverlayThreshold"},
       .appliesTo = fusedModes,
       .needs = kNone,
       .valueFor = [](const RenderSettings&, bool fusion) { return int(fusion); }},
      // A fused minip or average: the functional projection is the mean, not the maximum.
      {.id = F::FusionMean,
       .name = "fusion mean",
       .values = 2,
       .defines = {nullptr, "MVW_FUSION_MEAN 1"},
       .includes = nullptr,
       .uniforms = {},
       .appliesTo = takesFusionMean,
       .needs = F::Fusion,
       .valueFor = [](const RenderSettings& s,
                      bool) { return int(s.overlay.projection == FusionProjection::Mean); }},
      // Volumetric normal glyphs (Seipel 2007).
      {.id = F::Glyphs,
       .name = "glyphs",
       .values = 2,
       .defines = {nullptr, "MVW_GLYPHS 1"},
       .includes = glyphIncludes,
       .uniforms = {"uGlyphFromWorld", "uGlyphMapSize", "uGlyphInvMapSize", "uGlyphRadius",
                    "uGlyphMinSize", "uGlyphAlpha"},
       .setUniforms = setGlyphUniforms,
       .sharedUniforms = {"uGlyphCells"},
       .appliesTo = shadedModes,
       .needs = kNone,
       .valueFor = [](const RenderSettings& s, bool) { return int(s.glyphs.on); }},
      // Simple blending, eq. (1), instead of size and convexity control (eqs. 2-3).
      {.id = F::GlyphSimple,
       .name = "glyph simple blending",
       .values = 2,
       .defines = {nullptr, "MVW_GLYPH_SIMPLE 1"},
       .includes = nullptr,
       .uniforms = {},
       .appliesTo = shadedModes,
       .needs = F::Glyphs,
       .valueFor = [](const RenderSettings& s,
                      bool) { return int(s.glyphs.method == GlyphMethod::Simple); }},
      // GlyphShading's values, in its order: bumps (no define), dimples, both, kinds.
      {.id = F::GlyphShading,
       .name = "glyph shading",
       .values = static_cast<int>(GlyphShading::Count),
       .defines = {nullptr, "MVW_GLYPH_CONCAVE 1", "MVW_GLYPH_BOTH 1", "MVW_GLYPH_KINDS 1"},
       .includes = nullptr,
       .uniforms = {"uWorldFromGlyph", "uGlyphRadiusMm", "uGlyphLayerMm", "uGlyphScreenRadiusPx",
                    "uGlyphScreenSpacingPx", "uGlyphScreenRight", "uGlyphScreenUp"},
       .setUniforms = setGlyphKindsUniforms,
       .appliesTo = shadedModes,
       .needs = F::Glyphs,
       .valueFor = [](const RenderSettings& s,
                      bool) { return static_cast<int>(glyphShadingOf(s)); }},
      // The paper's placement, size rule and shading (its figures reproduced).
      {.id = F::GlyphPaper,
       .name = "glyph paper placement",
       .values = 2,
       .defines = {nullptr, "MVW_GLYPH_PAPER 1"},
       .includes = nullptr,
       .uniforms = {},
       .appliesTo = shadedModes,
       .needs = F::Glyphs,
       .valueFor = [](const RenderSettings& s,
                      bool) { return int(s.glyphMap.placement == GlyphPlacement::Paper); }},
      // The view's colour map instead of grey (common/colormap.glsl).
      {.id = F::ImageColormap,
       .name = "image colour map",
       .values = 2,
       .defines = {nullptr, "MVW_IMAGE_COLORMAP 1"},
       .includes = nullptr,
       .uniforms = {},
       .sharedUniforms = {"uImageColormap"},
       .appliesTo = takesImageColors,
       .needs = kNone,
       .valueFor = [](const RenderSettings& s, bool) { return int(s.imageColors.has_value()); }},
      // The anatomy on the crop's cut face (issue 36).
      {.id = F::CutFace,
       .name = "cut face",
       .values = 2,
       .defines = {nullptr, "MVW_CUT_FACE 1"},
       .includes = cutFaceIncludes,
       .uniforms = {},
       .sharedUniforms = {"uWindowLevel"},
       .appliesTo = shadedModes,
       .needs = kNone,
       .valueFor = [](const RenderSettings& s, bool) { return int(showsAnatomyOnCutFace(s)); }},
  }};
  return table;
}

bool featureCounts(const RaycastFeatureSpec& f, RenderMode mode, const RaycastVariants& v) {
  return v.on(f.id) && f.appliesTo(mode) && (f.needs == kNone || v.on(f.needs));
}

void setFeatureUniforms(const ShaderProgram& program, RenderMode mode, const RaycastVariants& v,
                        const FeatureFrame& frame) {
  for (const RaycastFeatureSpec& f : raycastFeatures())
    if (f.setUniforms && featureCounts(f, mode, v)) f.setUniforms(program, frame);
}

}  // namespace mvw::render::detail
