// View planning (study ViewPlan) without GL or files: planViews and its inverse describeView,
// which the viewer saves its panes with, the MPR planes' standard views, the overrides and the
// refusals of what a view cannot show.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "StudyTestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {
namespace {

// describeView is planViews' inverse: the config it writes plans back to the same renderer
// settings, field for field (the viewer saves its panes this way).
TEST(ViewPlan, DescribeViewIsTheInverseOfPlanViews) {
  const nlohmann::json view = {
      {"name", "a"},
      {"mode", "composite"},
      {"view", "superior"},
      {"azimuth", 12.5},
      {"elevation", -3},
      {"roll", 4},
      {"zoom", 1.7},
      {"perspective", true},
      {"width", 300},
      {"height", 200},
      {"preset", "ct-skin"},
      {"gradient_opacity", {5, 40}},
      {"functional_window", {0.3, 1.5}},
      {"functional_classes", 4},
      {"crop_min", {0, 0.1, 0}},
      {"crop_max", {1, 1, 0.55}},
      {"light", {-0.8, 0.8}},
      {"shading", false},
      {"sampling", "nearest"},
      {"step_mm", 0.3},
      {"jitter", false},
      {"seed", 9},
      {"background", {0.125, 0.25, 0.5}},  // exact in float, as the renderer holds it
      {"fusion", true},
      {"overlay_opacity", 0.75},
      {"overlay_threshold", 0.125},
      {"window", 900},
      {"level", 100},
      {"iso", 250},
      {"shells", 16},
      {"shells_disabled", {1, 2}},
      {"plane_offset_mm", 20},
      {"slab_mm", 5},
      {"overlay", false},
      {"segmentation_outlines", false},
      {"depth_cue", {{"brightness", 0.1}, {"amount", 0.66}, {"contrast", 0.33}}},
      {"glyphs",
       {{"method", "simple"},
        {"convexity", "both"},
        {"placement", "paper"},
        {"min_size", 0.5},
        {"diameter_mm", 9},
        {"count", 20},
        {"seed", 3},
        {"map_size", 96},
        {"map_diameter", 20}}}};
  const config::StudyConfig study = studyWith(view);
  const std::vector<PlannedView> planned = planViews(study);
  ASSERT_EQ(planned.size(), 1u);
  const config::ViewConfig back = describeView(planned[0].settings, "a", "ct-skin");
  EXPECT_EQ(config::viewConfigJson(back), config::viewConfigJson(study.render.views[0]));
  const std::vector<PlannedView> again = planViews(studyWith(config::viewConfigJson(back)));
  EXPECT_EQ(config::viewConfigJson(describeView(again[0].settings, "a", "ct-skin")),
            config::viewConfigJson(back));
}

TEST(ViewPlan, MprPlaneNamesAreTheirStandardViews) {
  EXPECT_EQ(standardView(config::ViewName::Axial), render::StandardView::Inferior);
  EXPECT_EQ(standardView(config::ViewName::Coronal), render::StandardView::Anterior);
  EXPECT_EQ(standardView(config::ViewName::Sagittal), render::StandardView::Left);
  for (int v = 0; v < 6; ++v) {
    const auto sv = static_cast<render::StandardView>(v);
    EXPECT_EQ(standardView(viewName(sv)), sv);
  }
}

TEST(ViewPlan, OverridesReplaceTheViewsOwnAndBadOnesAreBadInput) {
  const config::StudyConfig study = studyWith({{"mode", "composite"}});
  ViewOverrides o;
  o.mode = "mip";
  o.view = "axial";
  o.size = 64;
  const PlannedView p = planViews(study, o).at(0);
  EXPECT_EQ(p.settings.mode, RenderMode::Mip);
  EXPECT_EQ(p.settings.camera.view, render::StandardView::Inferior);
  EXPECT_EQ(p.settings.size, glm::ivec2(64, 64));
  o.mode = "xray";
  try {
    planViews(study, o);
    ADD_FAILURE() << "no InputError for --mode xray";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--mode 'xray'"), std::string::npos) << e.what();
  }
}

TEST(ViewPlan, GlyphsNeedAFunctionalVolumeAndASurfaceMode) {
  config::StudyConfig study = studyWith({{"glyphs", nlohmann::json::object()}});
  study.functional.reset();
  EXPECT_THROW(planViews(study), InputError);
  EXPECT_THROW(planViews(studyWith({{"mode", "mip"}, {"glyphs", nlohmann::json::object()}})),
               InputError);
}

// fusion_projection (issue 41): kept by describeView where the mode takes it (minip,
// average), refused where it does not (a fused mip takes the functional maximum), and fusion
// needs a functional volume.
TEST(ViewPlan, FusionProjectionIsForMinipAndAverage) {
  for (const char* mode : {"minip", "average"}) {
    const config::StudyConfig study =
        studyWith({{"mode", mode}, {"fusion", true}, {"fusion_projection", "mean"}});
    const PlannedView p = planViews(study).at(0);
    EXPECT_EQ(p.settings.overlay.projection, FusionProjection::Mean) << mode;
    EXPECT_EQ(describeView(p.settings, "view", "").overlay.projection, FusionProjection::Mean)
        << mode;
  }
  try {
    planViews(studyWith({{"mode", "mip"}, {"fusion", true}, {"fusion_projection", "mean"}}));
    ADD_FAILURE() << "no InputError for fusion_projection mean on a mip view";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fusion_projection mean is for minip and average"),
              std::string::npos)
        << e.what();
  }
  // --mode mip over a fused average with the mean: the mip's maximum, not a refusal.
  ViewOverrides o;
  o.mode = "mip";
  const PlannedView overridden =
      planViews(studyWith({{"mode", "average"}, {"fusion", true}, {"fusion_projection", "mean"}}),
                o)
          .at(0);
  EXPECT_EQ(overridden.settings.mode, RenderMode::Mip);
  EXPECT_EQ(overridden.settings.overlay.projection, FusionProjection::Max);
  config::StudyConfig none = studyWith({{"mode", "mip"}, {"fusion", true}});
  none.functional.reset();
  EXPECT_THROW(planViews(none), InputError);
}

}  // namespace
}  // namespace mvw::study
