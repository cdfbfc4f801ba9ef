#include "RaycastPrograms.h"

#include <set>
#include <utility>

namespace mvw::render::detail {

namespace {

bool has(RaycastVariants variants, RaycastVariant v) {
  return variants.test(static_cast<std::size_t>(v));
}

RaycastSource betaSource() { return {"fullscreen.vert.glsl", "beta.frag.glsl", {}}; }

}  // namespace

const ShaderProgram& RaycastPrograms::forMode(RenderMode mode, const RenderSettings& s,
                                              bool fusion) {
  const RaycastSource src = source(mode, layout_, variants(s, fusion));
  std::string key = toString(mode);
  for (const auto& d : src.defines) key += "+" + d;
  return cached(key, src);
}

const ShaderProgram& RaycastPrograms::beta() { return cached("beta", betaSource()); }

bool RaycastPrograms::usesBoxProxy(RenderMode mode) { return mode != RenderMode::Mpr; }

RaycastVariants RaycastPrograms::variants(const RenderSettings& s, bool fusion) {
  RaycastVariants v;
  auto set = [&v](RaycastVariant which, bool on) { v.set(static_cast<std::size_t>(which), on); };
  set(RaycastVariant::DepthCue, s.depthCue.on);
  set(RaycastVariant::Nearest, !s.linear);
  set(RaycastVariant::Tf2d, s.gradientOpacityHigh > 0.0);
  set(RaycastVariant::Fusion, fusion);
  set(RaycastVariant::FusionMean, s.overlay.projection == FusionProjection::Mean);
  set(RaycastVariant::Glyphs, s.glyphs);
  set(RaycastVariant::GlyphSimple, !s.glyphSizeControl);
  // Chosen labels carry their own kind (bump or dimple) through the "both" shading.
  // Other kinds (issue 40): the kinds' shading, each glyph's kind read at its foot.
  const bool kinds = usesGlyphKinds(s);
  const bool both = !kinds && (s.glyphConvexity == GlyphConvexity::Both || !s.glyphLabels.empty());
  set(RaycastVariant::GlyphConcave, !kinds && !both && s.glyphConvexity == GlyphConvexity::Dimples);
  set(RaycastVariant::GlyphBoth, both);
  set(RaycastVariant::GlyphKinds, kinds);
  set(RaycastVariant::GlyphPaper, s.glyphMap.placement == GlyphPlacement::Paper);
  set(RaycastVariant::ImageColormap, s.imageColors.has_value());
  set(RaycastVariant::CutFace, showsAnatomyOnCutFace(s));
  return v;
}

RaycastSource RaycastPrograms::source(RenderMode mode, VolumeLayout layout, RaycastVariants v) {
  RaycastSource out;
  out.vertex = usesBoxProxy(mode) ? "box.vert.glsl" : "fullscreen.vert.glsl";
  out.fragment = "projection.frag.glsl";
  std::vector<std::string>& defines = out.defines;
  const bool shaded = mode == RenderMode::Composite || mode == RenderMode::Isosurface;
  if (mode == RenderMode::Mip && has(v, RaycastVariant::DepthCue))
    defines.push_back("MVW_DEPTH_CUE 1");
  if (mode == RenderMode::Mip && has(v, RaycastVariant::Nearest))
    defines.push_back("MVW_NEAREST 1");
  if (mode == RenderMode::Composite) {
    if (has(v, RaycastVariant::Tf2d)) defines.push_back("MVW_TF2D 1");
    if (has(v, RaycastVariant::Fusion)) defines.push_back("MVW_FUSION 1");
  }
  // The fused projections: a program of their own, so that the plain ones keep their skipping.
  if (isProjectionMode(mode) && has(v, RaycastVariant::Fusion)) {
    defines.push_back("MVW_FUSION 1");
    if (takesFusionMean(mode) && has(v, RaycastVariant::FusionMean))
      defines.push_back("MVW_FUSION_MEAN 1");
  }
  if (shaded && has(v, RaycastVariant::Glyphs)) {
    defines.push_back("MVW_GLYPHS 1");
    if (has(v, RaycastVariant::GlyphSimple)) defines.push_back("MVW_GLYPH_SIMPLE 1");
    if (has(v, RaycastVariant::GlyphConcave)) defines.push_back("MVW_GLYPH_CONCAVE 1");
    if (has(v, RaycastVariant::GlyphBoth)) defines.push_back("MVW_GLYPH_BOTH 1");
    if (has(v, RaycastVariant::GlyphPaper)) defines.push_back("MVW_GLYPH_PAPER 1");
    if (has(v, RaycastVariant::GlyphKinds)) defines.push_back("MVW_GLYPH_KINDS 1");
  }
  if (shaded && has(v, RaycastVariant::CutFace)) defines.push_back("MVW_CUT_FACE 1");
  switch (mode) {
    case RenderMode::Composite:
      out.fragment = "composite.frag.glsl";
      break;
    case RenderMode::Isosurface:
      out.fragment = "isosurface.frag.glsl";
      break;
    case RenderMode::Mip:
      defines.push_back("MVW_MIP 1");
      break;
    case RenderMode::MinIp:
      defines.push_back("MVW_MINIP 1");
      break;
    case RenderMode::Average:
      defines.push_back("MVW_AVERAGE 1");
      break;
    case RenderMode::Mpr:
      out.fragment = "mpr.frag.glsl";
      break;
    case RenderMode::ShellMip:
    case RenderMode::ShellSum:
    case RenderMode::ShellLit:
      break;  // drawn by detail::ShellRenderer
  }
  if (has(v, RaycastVariant::ImageColormap) && takesImageColors(mode))
    defines.push_back("MVW_IMAGE_COLORMAP 1");
  if (layout == VolumeLayout::FoldedOnTheFly) defines.push_back("MVW_FOLDED 1");
  if (shaded && (layout == VolumeLayout::OnTheFly || layout == VolumeLayout::FoldedOnTheFly))
    defines.push_back("MVW_GRADIENT_ON_THE_FLY 1");
  if (shaded && layout == VolumeLayout::PackedGradient) {
    defines.push_back("MVW_PACKED_GRADIENT 1");
    // The packed texture is always trilinear: nearest-neighbour values keep the intensity's.
    if (mode == RenderMode::Composite && !has(v, RaycastVariant::Nearest))
      defines.push_back("MVW_PACKED_VALUE 1");
  }
  return out;
}

std::vector<RaycastSource> RaycastPrograms::every() {
  std::vector<RaycastSource> out;
  std::set<std::vector<std::string>> seen;
  auto add = [&](RaycastSource s) {
    std::vector<std::string> key = s.defines;
    key.push_back(s.vertex);
    key.push_back(s.fragment);
    if (seen.insert(std::move(key)).second) out.push_back(std::move(s));
  };
  // Through the modes' names, so that a mode added later is among them too.
  for (const std::string& name : renderModeNames()) {
    const RenderMode mode = *parseRenderMode(name);
    if (isShellMode(mode)) continue;
    for (int layout = 0; layout < static_cast<int>(VolumeLayout::Count); ++layout)
      for (unsigned long long bits = 0; bits < (1ull << RaycastVariants().size()); ++bits)
        add(source(mode, static_cast<VolumeLayout>(layout), RaycastVariants(bits)));
  }
  add(betaSource());
  return out;
}

const ShaderProgram& RaycastPrograms::cached(const std::string& key, const RaycastSource& source) {
  auto it = programs_.find(key);
  if (it == programs_.end())
    it =
        programs_.emplace(key, ShaderProgram(source.vertex, source.fragment, source.defines)).first;
  return it->second;
}

}  // namespace mvw::render::detail
