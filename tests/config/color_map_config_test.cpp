// A view's colour map and orbit keys in the study config (config ViewConfig): they round trip,
// and bad values are refused naming the key.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Error.h"

namespace mvw {
namespace {

using nlohmann::json;

std::string problemOf(const json& view) {
  try {
    config::parseViewConfig(view, "study.json", "render.views[0]", 0);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "study.json");
    return e.problem();
  }
  ADD_FAILURE() << "no InputError for " << view.dump();
  return {};
}

TEST(ColorMapConfig, KeysRoundTripAndBadValuesNameTheKey) {
  const config::ViewConfig v = config::parseViewConfig({{"mode", "mip"},
                                                        {"colormap", "grey-inverted"},
                                                        {"overlay_colormap", "pet-20-step"},
                                                        {"orbit", 36},
                                                        {"orbit_mode", "rock"},
                                                        {"orbit_range", 45},
                                                        {"orbit_fps", 15}},
                                                       "study.json", "render.views[0]", 0);
  EXPECT_EQ(v.colormap, ColorMap::GreyInverted);
  EXPECT_EQ(v.overlayColormap, ColorMap::Pet20Step);
  EXPECT_EQ(v.orbit, (Orbit{36, OrbitMode::Rock, 45, 15}));
  const json written = config::viewConfigJson(v);
  EXPECT_EQ(written["colormap"], "grey-inverted");
  EXPECT_EQ(written["orbit"], 36);
  EXPECT_EQ(config::viewConfigJson(config::parseViewConfig(written, "s.json", "v", 0)), written);
  // A still writes no orbit.
  EXPECT_FALSE(config::viewConfigJson(config::ViewConfig{}).contains("orbit"));

  EXPECT_NE(problemOf({{"mode", "mip"}, {"colormap", "rainbow"}})
                .find("'render.views[0].colormap' must be grey, grey-inverted, hot-iron"),
            std::string::npos);
  EXPECT_NE(problemOf({{"overlay_colormap", 3}}).find("'render.views[0].overlay_colormap'"),
            std::string::npos);
  EXPECT_NE(problemOf({{"colormap", "hot-iron"}}).find("'render.views[0].colormap' applies to mip"),
            std::string::npos);  // the default mode is composite
  for (const json& bad : {json(0), json(1), json(-5), json(721), json(1e9), json(2.5), json("10")})
    EXPECT_NE(problemOf({{"orbit", bad}}).find("'render.views[0].orbit' must be a whole number"),
              std::string::npos)
        << bad.dump();
  EXPECT_NE(problemOf({{"orbit", 8}, {"orbit_mode", "wobble"}}).find("must be spin or rock"),
            std::string::npos);
  EXPECT_NE(problemOf({{"orbit", 8}, {"orbit_range", 0}}).find("'render.views[0].orbit_range'"),
            std::string::npos);
  EXPECT_NE(problemOf({{"orbit", 8}, {"view", "superior"}}).find("long axis"), std::string::npos);
}

}  // namespace
}  // namespace mvw
