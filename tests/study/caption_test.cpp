// What a picture says about itself (study Caption): the caption under a view and the glyph
// legend, whose sizes follow the attribute window.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "StudyTestUtil.h"
#include "mvw/study/Caption.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {
namespace {

TEST(Caption, SaysWhatTheViewShows) {
  PlannedView mip =
      planViews(studyWith({{"mode", "mip"}, {"depth_cue", {{"brightness", 0.1}, {"amount", 0.5}}}}))
          .at(0);
  EXPECT_EQ(viewCaption(mip, {400, 40}), "mip  W 400 L 40  depth cue b0 0.10 a 0.50 b 1.00");
  PlannedView mpr =
      planViews(studyWith({{"mode", "mpr"}, {"view", "coronal"}, {"slab_mm", 10}})).at(0);
  EXPECT_EQ(viewCaption(mpr, {2000, 500}), "mpr coronal  slab 10 mm  W 2000 L 500");
  PlannedView glyphs =
      planViews(studyWith({{"preset", "ct-skin"}, {"glyphs", {{"convexity", "concave"}}}})).at(0);
  EXPECT_EQ(viewCaption(glyphs, {}), "composite  ct-skin  glyphs sized concave");
}

// A fusion is named only where the image shows one (issue 41): the fused projections say which
// functional projection they lay over the anatomy's; a shell mode, which cannot fuse, says none.
TEST(Caption, NamesAFusionOnlyWhereTheImageShowsIt) {
  PlannedView mip = planViews(studyWith({{"mode", "mip"}, {"fusion", true}})).at(0);
  EXPECT_EQ(viewCaption(mip, {400, 40}), "mip  W 400 L 40  + colour fusion (functional max)");
  PlannedView average =
      planViews(studyWith({{"mode", "average"}, {"fusion", true}, {"fusion_projection", "mean"}}))
          .at(0);
  EXPECT_EQ(viewCaption(average, {400, 40}),
            "average  W 400 L 40  + colour fusion (functional mean)");
  PlannedView shells = planViews(studyWith({{"mode", "shells-mip"}, {"fusion", true}})).at(0);
  EXPECT_EQ(viewCaption(shells, {}).find("fusion"), std::string::npos) << viewCaption(shells, {});
  PlannedView plain = planViews(studyWith({{"mode", "mip"}})).at(0);
  EXPECT_EQ(viewCaption(plain, {400, 40}), "mip  W 400 L 40");
}
// The legend says what the bump sizes mean: none at or below the window, then the minimum
// size just above its low end up to full size at its high end (dimples below the middle for
// "both").
TEST(GlyphLegend, SizesFollowTheAttributeWindow) {
  PlannedView v =
      planViews(studyWith({{"glyphs", nlohmann::json::object()}, {"functional_window", {2.5, 8}}}))
          .at(0);
  const render::GlyphLegend legend = glyphLegend(v, "SUVbw", {0, 20});
  EXPECT_EQ(legend.title, "glyphs: SUVbw");
  ASSERT_EQ(legend.entries.size(), 4u);
  EXPECT_EQ(legend.entries[0].size, 0.0);
  EXPECT_EQ(legend.entries[1].label, "> 2.5");
  EXPECT_NEAR(legend.entries[1].size, 0.6, 1e-3);
  EXPECT_EQ(legend.entries[2].label, "5.25");
  EXPECT_DOUBLE_EQ(legend.entries[2].size, 0.8);
  EXPECT_DOUBLE_EQ(legend.entries[3].size, 1.0);
  v.settings.glyphs.convexity = GlyphConvexity::Both;
  const render::GlyphLegend both = glyphLegend(v, "SUVbw", {0, 20});
  ASSERT_EQ(both.entries.size(), 5u);
  EXPECT_EQ(both.entries[1].kind, GlyphKind::Dimples);
  EXPECT_EQ(both.entries[4].kind, GlyphKind::Bumps);
  v.settings.glyphs.on = false;
  EXPECT_TRUE(glyphLegend(v, "SUVbw", {0, 20}).entries.empty());
}

}  // namespace
}  // namespace mvw::study
