#pragma once
// Text and marks burned into headless renders (OpenCV Hershey fonts): orientation labels at
// the four edges, a scale bar in mm (orthographic views), and a caption (mode, window/level).
#include <optional>
#include <string>
#include <vector>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Image.h"
#include "mvw/core/RenderMode.h"
#include "mvw/render/Camera.h"

namespace mvw::render {

// The patient side a world (LPS) direction points toward: "L", "P", "S", ... with a second
// letter for directions more than ~22 degrees off the main axis ("LA").
std::string orientationLabel(const glm::dvec3& worldDirection);

void annotate(Image& image, const Camera& camera, const std::string& caption);

// A vertical colour bar (hot metal, or `table`) at the right edge, labelled with the value range,
// the unit ("no unit" where none is known) and, above it, `title`: the volume it shows.
void drawColourBar(Image& image, double lo, double hi, const std::string& unit,
                   const std::string& title = "");
void drawColourBar(Image& image, double lo, double hi, const std::string& unit,
                   const ColorTable& table, const std::string& title = "");

// A glyph legend (issue 15): what a bump's size or kind means. size: the apparent bump radius
// as a fraction of the glyph radius (0: no glyph); the icons keep the sizes' ratios.
struct GlyphLegendEntry {
  std::string label;
  double size = 1.0;
  GlyphKind kind = GlyphKind::Bumps;
  // The glyph as the view's shader draws it (issue 40: VolumeRenderer::renderGlyphIcon), drawn
  // instead of the hand-shaded bump when present.
  Image icon;
  // The attribute value the entry stands for (the functional volume's unit, or the label
  // number), from which the icon is rendered; none: no icon (a hand-shaded bump).
  std::optional<double> value;
};
struct GlyphLegend {
  std::string title;
  std::vector<GlyphLegendEntry> entries;
  double low = 0.0, high = 0.0;  // the attribute window the entries' values go through
};

// The legend at the top-left corner: its title, then per entry a shaded bump (lit from the
// upper left, as the renders are) or dimple and its label.
void drawGlyphLegend(Image& image, const GlyphLegend& legend);

}  // namespace mvw::render
