#pragma once
// The glyph legend's icons (issue 40, internal to mvw_render): each entry's glyph drawn by the
// view's own glyph shading (shaders/common/glyphs.glsl), on a small plane facing the camera
// through one glyph's centre, with the view's light, colours, map and attribute mapping, the
// attribute there being the value the entry stands for. So the legend and the image match.
#include <memory>

#include "mvw/render/Annotations.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/RenderSettings.h"

namespace mvw::render {
class VolumeRenderer;
}

namespace mvw::render::detail {

class GlyphIcons {
 public:
  GlyphIcons();
  ~GlyphIcons();
  // Fills the icon of every entry of `legend` that has a value (pixels square).
  void fill(GlContext& context, const RenderSettings& view, GlyphLegend& legend, int pixels);

 private:
  std::unique_ptr<VolumeRenderer> renderer_;  // on the plane for the map below
  GlyphMapSettings map_{0, 0, 0.0, 0};
  double diameterMm_ = 0.0;
  glm::dmat4 worldFromIndex_{1.0};
  glm::ivec3 dims_{0};
};

}  // namespace mvw::render::detail
