#pragma once
// What an annotated view shows over its render, and the one painter that burns it in: `mvw
// render`'s views and the viewer's panes are drawn by it (tests/view/viewer-xvfb compares the
// panes as shown with annotated headless renders byte for byte).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/Camera.h"
#include "mvw/render/RenderSettings.h"
#include "mvw/render/SegmentLegend.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/SegmentOverlay.h"

namespace mvw::output {

// A colour bar at the right edge: the values from low to high in `unit`, `colors` (none: hot
// metal), and `title`, the volume it shows.
struct ColourBar {
  double low = 0.0, high = 0.0;
  std::string unit;
  std::optional<ColorTable> colors;
  std::string title;
};

struct ViewAnnotations {
  std::string caption;              // with the orientation labels and the scale bar
  render::GlyphLegend glyphLegend;  // no entries: none
  std::optional<ColourBar> colourBar;
  std::vector<render::LegendEntry> segmentLegend;  // empty: none
};

// The bar of the map a view shows: the overlay's or fusion's over the functional window (the
// view's own, else `functionalRange`), else the image's own colour map over `shown` (the window
// the projection or MPR used), in the anatomy's unit; a grey image has none.
std::optional<ColourBar> colourBarOf(const render::RenderSettings& settings,
                                     const Volume& anatomical, const Volume* functional,
                                     std::pair<double, double> functionalRange,
                                     const WindowLevel& shown);

// The legend of the segments an MPR view outlines (empty for other views, or none outlined).
std::vector<render::LegendEntry> segmentLegendOf(const render::RenderSettings& settings,
                                                 const study::SegmentOverlay* segments);

// Burns `annotations` into `image` (rendered with `settings` through `camera`): caption,
// orientation labels and scale bar, the glyph legend (with glyph kinds, each icon first drawn
// by `renderer`'s own glyph shading), the colour bar, the segments' legend.
void drawAnnotations(Image& image, const render::Camera& camera,
                     const render::RenderSettings& settings, ViewAnnotations& annotations,
                     render::VolumeRenderer& renderer);

}  // namespace mvw::output
