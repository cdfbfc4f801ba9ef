#include "mvw/output/ViewAnnotations.h"

#include "mvw/study/Caption.h"

namespace mvw::output {

std::optional<ColourBar> colourBarOf(const render::RenderSettings& s, const Volume& anatomical,
                                     const Volume* functional,
                                     std::pair<double, double> functionalRange,
                                     const WindowLevel& shown) {
  if (render::showsFunctional(s, functional != nullptr)) {
    const auto [flo, fhi] =
        s.functionalWindow.orRange(functionalRange.first, functionalRange.second);
    return ColourBar{flo, fhi, functional->metadata().unit, s.overlayColors,
                     study::volumeName(*functional, "functional")};
  }
  if (render::showsImageColors(s))
    return ColourBar{shown.level - 0.5 * shown.window, shown.level + 0.5 * shown.window,
                     anatomical.metadata().unit, s.imageColors,
                     study::volumeName(anatomical, "anatomical")};
  return std::nullopt;
}

std::vector<render::LegendEntry> segmentLegendOf(const render::RenderSettings& s,
                                                 const study::SegmentOverlay* segments) {
  std::vector<render::LegendEntry> legend;
  if (!segments || s.mode != render::RenderMode::Mpr || !s.segmentationOutlines) return legend;
  for (std::size_t i = 0; i < segments->names.size(); ++i)
    legend.push_back({segments->names[i], segments->colours[i]});
  return legend;
}

void drawAnnotations(Image& image, const render::Camera& camera, const render::RenderSettings& s,
                     ViewAnnotations& a, render::VolumeRenderer& renderer) {
  render::annotate(image, camera, a.caption);
  // Glyph kinds (issue 40): each icon drawn by the view's own glyph shading.
  if (render::usesGlyphKinds(s)) renderer.renderGlyphIcons(s, a.glyphLegend);
  render::drawGlyphLegend(image, a.glyphLegend);
  if (const std::optional<ColourBar>& bar = a.colourBar) {
    if (bar->colors)
      render::drawColourBar(image, bar->low, bar->high, bar->unit, *bar->colors, bar->title);
    else
      render::drawColourBar(image, bar->low, bar->high, bar->unit, bar->title);
  }
  if (!a.segmentLegend.empty()) render::drawSegmentLegend(image, a.segmentLegend);
}

}  // namespace mvw::output
