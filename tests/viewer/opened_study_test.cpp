// A study opened in the viewer (mvw/viewer/OpenedStudy.h) without GL: the segments' centres
// the reader jumps to, and each pane's annotations as `mvw render`'s painter gets them.
#include "mvw/viewer/OpenedStudy.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "ViewerTestUtil.h"
#include "mvw/core/WindowLevel.h"

namespace mvw::viewer {
namespace {

using OpenedStudyTest = ViewerFixture;

study::SegmentOverlay twoSegments() {
  study::SegmentOverlay o;
  o.masks = Volume({4, 4, 4}, 3, ScalarType::UInt8,
                   makeWorldFromIndex({10.0, 20.0, 30.0}, {2.0, 2.0, 2.0}, glm::dmat3(1.0)));
  o.masks.setValue(0, 0, 0, 0, 1.0);  // segment 0: voxels (0,0,0) and (2,0,0)
  o.masks.setValue(2, 0, 0, 0, 1.0);
  o.masks.setValue(3, 3, 3, 2, 1.0);  // segment 1 has no voxel; segment 2 one
  o.names = {"liver", "empty", "lesion"};
  o.numbers = {1, 2, 3};
  return o;
}

TEST(OpenedStudy, SegmentCentresAreTheMeanVoxelCentre) {
  const auto centres = segmentCentres(twoSegments(), glm::dmat4(1.0));
  ASSERT_EQ(centres.size(), 2u);  // the empty segment has no centre
  EXPECT_EQ(centres[0].first, "liver");
  EXPECT_EQ(centres[0].second, glm::dvec3(12.0, 20.0, 30.0));
  EXPECT_EQ(centres[1].first, "lesion");
  EXPECT_EQ(centres[1].second, glm::dvec3(16.0, 26.0, 36.0));
}

TEST(OpenedStudy, SegmentCentresArePlaced) {
  const glm::dmat4 placed = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, -2.0, 3.0));
  const auto centres = segmentCentres(twoSegments(), placed);
  ASSERT_EQ(centres.size(), 2u);
  EXPECT_EQ(centres[0].second, glm::dvec3(13.0, 18.0, 33.0));
}

TEST_F(OpenedStudyTest, PaneAnnotationsAreTheStatesWithRendersColourBar) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  for (int p = 0; p < kPaneCount; ++p) {
    const render::RenderSettings s = state.renderSettings(p);
    const output::ViewAnnotations a = paneAnnotations(state, p, s, {0.0, 1.0}, nullptr);
    EXPECT_EQ(a.caption, state.caption(p, s));
    EXPECT_EQ(a.glyphLegend.entries.size(), state.glyphLegend(p, s).entries.size());
    const auto [lo, hi] = state.scene().valueRange;
    const auto bar =
        output::colourBarOf(s, ct, nullptr, {0.0, 1.0}, windowOrFullRange(s.window, lo, hi));
    // Where `mvw render` draws none (a grey image), the viewer's pane still carries its grey
    // scale: every pane that maps values has a bar.
    ASSERT_EQ(a.colourBar.has_value(), bar.has_value() || takesImageColors(s.mode)) << p;
    if (bar) {
      EXPECT_EQ(a.colourBar->low, bar->low);
      EXPECT_EQ(a.colourBar->high, bar->high);
      EXPECT_EQ(a.colourBar->title, bar->title);
    } else if (a.colourBar) {
      const WindowLevel w = windowOrFullRange(s.window, lo, hi);
      EXPECT_EQ(a.colourBar->low, w.level - 0.5 * w.window);
      EXPECT_EQ(a.colourBar->high, w.level + 0.5 * w.window);
      ASSERT_TRUE(a.colourBar->colors.has_value());
      EXPECT_EQ(a.colourBar->colors->map, ColorMap::Grey);
      EXPECT_EQ(a.colourBar->unit, "HU");
    }
    EXPECT_TRUE(a.segmentLegend.empty());
  }
}

TEST_F(OpenedStudyTest, TheFunctionalPaneBarIsItsOwnWindow) {
  ViewerScene scene = sceneOf(ct);
  scene.functionalRange = pet.valueRange();
  ViewerState state(study, ct, &pet, scene);
  state.setLayout(config::ViewerLayout::PetCtAxial);
  renderAll(state);
  int shown = 0;
  for (int p = 0; p < kPaneCount; ++p) {
    if (!state.paneShowsFunctional(p)) continue;
    ++shown;
    const render::RenderSettings s = state.renderSettings(p);
    const output::ViewAnnotations a = paneAnnotations(state, p, s, {0.0, 10.0}, nullptr);
    ASSERT_TRUE(a.colourBar);
    EXPECT_DOUBLE_EQ(a.colourBar->low, s.window.level - 0.5 * s.window.window);
    EXPECT_DOUBLE_EQ(a.colourBar->high, s.window.level + 0.5 * s.window.window);
    EXPECT_EQ(a.colourBar->title, ViewerState::volumeName(pet, "functional"));
  }
  EXPECT_EQ(shown, 1);
}

}  // namespace
}  // namespace mvw::viewer
