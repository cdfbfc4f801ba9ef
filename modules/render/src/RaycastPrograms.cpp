#include "RaycastPrograms.h"

namespace mvw::render::detail {

const ShaderProgram& RaycastPrograms::forMode(RenderMode mode, const RenderSettings& s,
                                              bool fusion) {
  std::string file = "projection.frag.glsl";
  std::vector<std::string> defines;
  if (mode == RenderMode::Mip && s.depthCue) defines.push_back("MVW_DEPTH_CUE 1");
  if (mode == RenderMode::Mip && !s.linear) defines.push_back("MVW_NEAREST 1");
  if (mode == RenderMode::Composite) {
    if (s.gradientOpacityHigh > 0.0) defines.push_back("MVW_TF2D 1");
    if (fusion) defines.push_back("MVW_FUSION 1");
  }
  if ((mode == RenderMode::Composite || mode == RenderMode::Isosurface) && s.glyphs) {
    defines.push_back("MVW_GLYPHS 1");
    if (!s.glyphSizeControl) defines.push_back("MVW_GLYPH_SIMPLE 1");
    // Chosen labels carry their own kind (bump or dimple) through the "both" shading.
    const bool both = s.glyphConvexity == GlyphConvexity::Both || !s.glyphLabels.empty();
    if (!both && s.glyphConvexity == GlyphConvexity::Dimples)
      defines.push_back("MVW_GLYPH_CONCAVE 1");
    if (both) defines.push_back("MVW_GLYPH_BOTH 1");
    if (s.glyphMap.placement == GlyphPlacement::Paper) defines.push_back("MVW_GLYPH_PAPER 1");
  }
  switch (mode) {
    case RenderMode::Composite:
      file = "composite.frag.glsl";
      break;
    case RenderMode::Isosurface:
      file = "isosurface.frag.glsl";
      break;
    case RenderMode::Mip:
      defines.push_back("MVW_MIP 1");
      break;
    case RenderMode::MinIp:
      defines = {"MVW_MINIP 1"};
      break;
    case RenderMode::Average:
      defines = {"MVW_AVERAGE 1"};
      break;
    case RenderMode::Mpr:
      file = "mpr.frag.glsl";
      break;
    case RenderMode::ShellMip:
    case RenderMode::ShellSum:
    case RenderMode::ShellLit:
      break;  // drawn by detail::ShellRenderer
  }
  if (s.imageColors && takesImageColors(mode)) defines.push_back("MVW_IMAGE_COLORMAP 1");
  if (folded_) defines.push_back("MVW_FOLDED 1");
  if (gradientOnTheFly_ && (mode == RenderMode::Composite || mode == RenderMode::Isosurface))
    defines.push_back("MVW_GRADIENT_ON_THE_FLY 1");
  if (packedGradient_ && (mode == RenderMode::Composite || mode == RenderMode::Isosurface)) {
    defines.push_back("MVW_PACKED_GRADIENT 1");
    // The packed texture is always trilinear: nearest-neighbour values keep the intensity's.
    if (mode == RenderMode::Composite && s.linear) defines.push_back("MVW_PACKED_VALUE 1");
  }
  std::string key = toString(mode);
  for (const auto& d : defines) key += "+" + d;
  return cached(key, usesBoxProxy(mode) ? "box.vert.glsl" : "fullscreen.vert.glsl", file, defines);
}

const ShaderProgram& RaycastPrograms::beta() {
  return cached("beta", "fullscreen.vert.glsl", "beta.frag.glsl", {});
}

bool RaycastPrograms::usesBoxProxy(RenderMode mode) { return mode != RenderMode::Mpr; }

const ShaderProgram& RaycastPrograms::cached(const std::string& key, const std::string& vertex,
                                             const std::string& fragment,
                                             const std::vector<std::string>& defines) {
  auto it = programs_.find(key);
  if (it == programs_.end())
    it = programs_.emplace(key, ShaderProgram(vertex, fragment, defines)).first;
  return it->second;
}

}  // namespace mvw::render::detail
