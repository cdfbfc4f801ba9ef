// What the annotation painter (output::ViewAnnotations, `mvw render`'s and the viewer's) shows
// of a view, decided without GL: which colour bar over which values, and the segments' legend.
#include <optional>

#include <gtest/gtest.h>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Volume.h"
#include "mvw/output/ViewAnnotations.h"
#include "mvw/study/SegmentOverlay.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::output {
namespace {

Volume volume(const std::string& modality, const std::string& unit) {
  Volume v({2, 2, 2}, 1, ScalarType::Float32, glm::dmat4(1.0));
  v.metadata().modality = modality;
  v.metadata().unit = unit;
  v.metadata().seriesDescription = modality == "PT" ? "FDG" : "Head";
  return v;
}

TEST(ViewAnnotations, AGreyImageHasNoColourBar) {
  const Volume ct = volume("CT", "HU");
  render::RenderSettings s;
  s.mode = RenderMode::Mip;
  EXPECT_FALSE(colourBarOf(s, ct, nullptr, {0.0, 1.0}, {400.0, 40.0}));
}

TEST(ViewAnnotations, AColouredImageShowsItsMapOverTheWindowItUsed) {
  const Volume ct = volume("CT", "HU");
  render::RenderSettings s;
  s.mode = RenderMode::Mip;
  s.imageColors = study::colorTable(ColorMap::HotIron);
  const std::optional<ColourBar> bar = colourBarOf(s, ct, nullptr, {0.0, 1.0}, {400.0, 40.0});
  ASSERT_TRUE(bar);
  EXPECT_DOUBLE_EQ(bar->low, -160.0);
  EXPECT_DOUBLE_EQ(bar->high, 240.0);
  EXPECT_EQ(bar->unit, "HU");
  ASSERT_TRUE(bar->colors);
  EXPECT_EQ(bar->colors->map, ColorMap::HotIron);
  EXPECT_EQ(bar->title, "CT Head");
  // A mode that takes no colour map shows none, whatever the settings hold.
  s.mode = RenderMode::Composite;
  EXPECT_FALSE(colourBarOf(s, ct, nullptr, {0.0, 1.0}, {400.0, 40.0}));
}

TEST(ViewAnnotations, AnOverlayShowsTheFunctionalWindowInTheFunctionalUnit) {
  const Volume ct = volume("CT", "HU"), pet = volume("PT", "SUVbw");
  render::RenderSettings s;
  s.mode = RenderMode::Mpr;
  s.imageColors = study::colorTable(ColorMap::HotIron);  // the overlay's bar wins
  std::optional<ColourBar> bar = colourBarOf(s, ct, &pet, {0.5, 12.0}, {400.0, 40.0});
  ASSERT_TRUE(bar);
  EXPECT_DOUBLE_EQ(bar->low, 0.5);
  EXPECT_DOUBLE_EQ(bar->high, 12.0);
  EXPECT_EQ(bar->unit, "SUVbw");
  EXPECT_FALSE(bar->colors);  // hot metal
  EXPECT_EQ(bar->title, "PET FDG");
  s.functionalWindow = {1.0, 6.0};
  s.overlayColors = study::colorTable(ColorMap::Pet);
  bar = colourBarOf(s, ct, &pet, {0.5, 12.0}, {400.0, 40.0});
  ASSERT_TRUE(bar);
  EXPECT_DOUBLE_EQ(bar->low, 1.0);
  EXPECT_DOUBLE_EQ(bar->high, 6.0);
  ASSERT_TRUE(bar->colors);
  EXPECT_EQ(bar->colors->map, ColorMap::Pet);
  // The overlay switched off: the image's own map again.
  s.overlay.mpr = false;
  bar = colourBarOf(s, ct, &pet, {0.5, 12.0}, {400.0, 40.0});
  ASSERT_TRUE(bar);
  EXPECT_EQ(bar->unit, "HU");
}

TEST(ViewAnnotations, OnlyOutliningMprViewsListTheSegments) {
  study::SegmentOverlay segments;
  segments.names = {"liver", "spleen"};
  segments.colours = {glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
  render::RenderSettings s;
  s.mode = RenderMode::Mpr;
  EXPECT_TRUE(segmentLegendOf(s, nullptr).empty());
  const std::vector<render::LegendEntry> legend = segmentLegendOf(s, &segments);
  ASSERT_EQ(legend.size(), 2u);
  EXPECT_EQ(legend[1].name, "spleen");
  EXPECT_EQ(legend[1].colour, glm::vec3(0.0f, 1.0f, 0.0f));
  s.segmentationOutlines = false;
  EXPECT_TRUE(segmentLegendOf(s, &segments).empty());
  s.segmentationOutlines = true;
  s.mode = RenderMode::Composite;
  EXPECT_TRUE(segmentLegendOf(s, &segments).empty());
}

}  // namespace
}  // namespace mvw::output
