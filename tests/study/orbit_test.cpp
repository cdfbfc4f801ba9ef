// Rotating views without GL: the --orbit and --colormap overrides (study planViews), checked
// before any work is done (the azimuths: tests/core/orbit_test.cpp).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Error.h"
#include "mvw/study/ViewPlan.h"

namespace mvw {
namespace {

TEST(Orbit, OverridesAreCheckedBeforeAnyWork) {
  config::StudyConfig study;
  study.file = "study.json";
  config::ViewConfig mip;
  mip.name = "mip";
  mip.mode = RenderMode::Mip;
  config::ViewConfig dvr;
  dvr.name = "dvr";
  study.render.views = {mip, dvr};
  study::ViewOverrides o;
  o.colormap = "hot-iron";
  o.orbit = 12;
  const auto views = study::planViews(study, o);
  ASSERT_EQ(views.size(), 2u);
  // --colormap reaches the views that take one; --orbit every view.
  ASSERT_TRUE(views[0].settings.imageColors);
  EXPECT_EQ(views[0].settings.imageColors->map, ColorMap::HotIron);
  EXPECT_FALSE(views[1].settings.imageColors);
  EXPECT_EQ(views[0].config.orbit.frames, 12);
  EXPECT_EQ(views[1].config.orbit.frames, 12);
  // Defaults: no tables, so the renderer draws exactly what it drew before colour maps.
  const auto plain = study::planViews(study, {});
  EXPECT_FALSE(plain[0].settings.imageColors);
  EXPECT_FALSE(plain[0].settings.overlayColors);
  // The inverse keeps the maps.
  o.overlayColormap = "pet";
  const auto coloured = study::planViews(study, o);
  const config::ViewConfig back = study::describeView(coloured[0].settings, "mip", "");
  EXPECT_EQ(back.colormap, ColorMap::HotIron);
  EXPECT_EQ(back.overlayColormap, ColorMap::Pet);

  auto problem = [&](const study::ViewOverrides& bad) {
    try {
      study::planViews(study, bad);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "study.json");
      return std::string(e.problem());
    }
    return std::string("no error");
  };
  for (int n : {0, 1, -3, 721, 1000000}) {
    study::ViewOverrides bad;
    bad.orbit = n;
    EXPECT_NE(problem(bad).find("--orbit must be 2..720"), std::string::npos) << n;
  }
  study::ViewOverrides badMap;
  badMap.colormap = "jet";
  EXPECT_NE(problem(badMap).find("--colormap 'jet' is not a colour map"), std::string::npos);
  config::StudyConfig dvrOnly = study;
  dvrOnly.render.views = {dvr};
  study::ViewOverrides colours;
  colours.colormap = "pet";
  try {
    study::planViews(dvrOnly, colours);
    ADD_FAILURE() << "--colormap on a study without projections";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.problem()).find("--colormap colours mip, minip, average and mpr"),
              std::string::npos);
  }
  study::ViewOverrides badMode;
  badMode.orbitMode = "tumble";
  EXPECT_NE(problem(badMode).find("--orbit-mode"), std::string::npos);
  study::ViewOverrides along;
  along.orbit = 8;
  along.view = "axial";
  EXPECT_NE(problem(along).find("every view of the study looks along it"), std::string::npos);
  // With a view along the axis among others, --orbit turns the others only.
  config::ViewConfig axial;
  axial.name = "axial";
  axial.mode = RenderMode::Mpr;
  axial.view = config::ViewName::Axial;
  study.render.views.push_back(axial);
  study::ViewOverrides some;
  some.orbit = 6;
  const auto mixed = study::planViews(study, some);
  EXPECT_EQ(mixed[0].config.orbit.frames, 6);
  EXPECT_EQ(mixed[2].config.orbit.frames, 0);
}

}  // namespace
}  // namespace mvw
