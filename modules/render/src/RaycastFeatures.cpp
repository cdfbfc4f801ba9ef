#include "RaycastFeatures.h"

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
  if (s.glyphConvexity == GlyphConvexity::Both || !s.glyphLabels.empty()) return GlyphShading::Both;
  return s.glyphConvexity == GlyphConvexity::Dimples ? GlyphShading::Dimples : GlyphShading::Bumps;
}

constexpr RaycastFeature kNone = RaycastFeature::Count;

std::vector<const char*> fusionIncludes(RenderMode m) {
  if (isProjectionMode(m)) return {"raycast/fusion-projection.glsl"};
  return {};  // composite: common/functional.glsl's fuseColour, which it includes itself
}
std::vector<const char*> glyphIncludes(RenderMode) { return {"common/glyphs.glsl"}; }
std::vector<const char*> cutFaceIncludes(RenderMode) { return {"raycast/cutface.glsl"}; }

}  // namespace

const std::array<RaycastFeatureSpec, kRaycastFeatureCount>& raycastFeatures() {
  using F = RaycastFeature;
  static const std::array<RaycastFeatureSpec, kRaycastFeatureCount> table{{
      // Heidrich, McCool and Stevens' depth-cued MIP (raycast/accumulate-mip.glsl).
      {F::DepthCue,
       "depth cue",
       2,
       {nullptr, "MVW_DEPTH_CUE 1"},
       nullptr,
       {"uCue", "uBoundingSphere"},
       onlyMip,
       kNone,
       [](const RenderSettings& s, bool) { return int(s.depthCue); }},
      // Nearest-neighbour samples: MIP drops its pre-pass (accumulate-mip.glsl); composite with
      // the packed gradient reads the value from the intensity, not the always trilinear packed
      // texture (RaycastPrograms::source's layout defines). The texture's filter:
      // VolumeTextures::setLinear.
      {F::Nearest,
       "nearest",
       2,
       {nullptr, "MVW_NEAREST 1"},
       nullptr,
       {},
       onlyMip,
       kNone,
       [](const RenderSettings& s, bool) { return int(!s.linear); }},
      // Composite's 2D transfer function over value and gradient magnitude.
      {F::Tf2d,
       "2D transfer function",
       2,
       {nullptr, "MVW_TF2D 1"},
       nullptr,
       {"uGradientScale", "uGradientRows"},
       onlyComposite,
       kNone,
       [](const RenderSettings& s, bool) { return int(s.gradientOpacityHigh > 0.0); }},
      // Colour fusion: composite blends the functional colour in per sample (common/
      // functional.glsl); a fused projection lays the functional volume's own projection over
      // the anatomy's (raycast/fusion-projection.glsl, with the fused block grid).
      {F::Fusion,
       "fusion",
       2,
       {nullptr, "MVW_FUSION 1"},
       fusionIncludes,
       {"uFunctionalFromWorld", "uColormap", "uOverlayOpacity", "uOverlayThreshold"},
       fusedModes,
       kNone,
       [](const RenderSettings&, bool fusion) { return int(fusion); }},
      // A fused minip or average: the functional projection is the mean, not the maximum.
      {F::FusionMean,
       "fusion mean",
       2,
       {nullptr, "MVW_FUSION_MEAN 1"},
       nullptr,
       {},
       takesFusionMean,
       F::Fusion,
       [](const RenderSettings& s, bool) {
         return int(s.fusionProjection == FusionProjection::Mean);
       }},
      // Volumetric normal glyphs (Seipel 2007).
      {F::Glyphs,
       "glyphs",
       2,
       {nullptr, "MVW_GLYPHS 1"},
       glyphIncludes,
       {"uGlyphCells", "uGlyphFromWorld", "uGlyphMapSize", "uGlyphInvMapSize", "uGlyphRadius",
        "uGlyphMinSize", "uGlyphAlpha"},
       shadedModes,
       kNone,
       [](const RenderSettings& s, bool) { return int(s.glyphs); }},
      // Simple blending, eq. (1), instead of size and convexity control (eqs. 2-3).
      {F::GlyphSimple,
       "glyph simple blending",
       2,
       {nullptr, "MVW_GLYPH_SIMPLE 1"},
       nullptr,
       {},
       shadedModes,
       F::Glyphs,
       [](const RenderSettings& s, bool) { return int(!s.glyphSizeControl); }},
      // GlyphShading's values, in its order.
      {F::GlyphShading,
       "glyph shading",
       static_cast<int>(GlyphShading::Count),
       {nullptr, "MVW_GLYPH_CONCAVE 1", "MVW_GLYPH_BOTH 1", "MVW_GLYPH_KINDS 1"},
       nullptr,
       {"uWorldFromGlyph", "uGlyphRadiusMm", "uGlyphLayerMm", "uGlyphScreenRadiusPx",
        "uGlyphScreenSpacingPx", "uGlyphScreenRight", "uGlyphScreenUp"},
       shadedModes,
       F::Glyphs,
       [](const RenderSettings& s, bool) { return static_cast<int>(glyphShadingOf(s)); }},
      // The paper's placement, size rule and shading (its figures reproduced).
      {F::GlyphPaper,
       "glyph paper placement",
       2,
       {nullptr, "MVW_GLYPH_PAPER 1"},
       nullptr,
       {},
       shadedModes,
       F::Glyphs,
       [](const RenderSettings& s, bool) {
         return int(s.glyphMap.placement == GlyphPlacement::Paper);
       }},
      // The view's colour map instead of grey (common/colormap.glsl).
      {F::ImageColormap,
       "image colour map",
       2,
       {nullptr, "MVW_IMAGE_COLORMAP 1"},
       nullptr,
       {"uImageColormap"},
       takesImageColors,
       kNone,
       [](const RenderSettings& s, bool) { return int(s.imageColors.has_value()); }},
      // The anatomy on the crop's cut face (issue 36).
      {F::CutFace,
       "cut face",
       2,
       {nullptr, "MVW_CUT_FACE 1"},
       cutFaceIncludes,
       {"uWindowLevel"},
       shadedModes,
       kNone,
       [](const RenderSettings& s, bool) { return int(showsAnatomyOnCutFace(s)); }},
  }};
  return table;
}

bool featureCounts(const RaycastFeatureSpec& f, RenderMode mode, const RaycastVariants& v) {
  return v.on(f.id) && f.appliesTo(mode) && (f.needs == kNone || v.on(f.needs));
}

}  // namespace mvw::render::detail
