// What the viewer panel's sliders do to the 3D view's settings (mvw/viewer/ViewControls.h):
// the glyph spacing and the functional attribute's window.
#include "mvw/viewer/ViewControls.h"

#include <gtest/gtest.h>

#include "mvw/core/GlyphDefaults.h"
#include "mvw/render/GlyphMap.h"

namespace mvw::viewer {
namespace {

TEST(ViewControls, GlyphSpacingRoundTrips) {
  render::RenderSettings v;
  v.glyphMap = render::blueNoiseGlyphMap(8.0, kBlueNoiseDiameterFraction * 8.0, 7);
  v.glyphDiameterMm = kBlueNoiseDiameterFraction * 8.0;
  setGlyphSpacingMm(v, 12.0);
  EXPECT_DOUBLE_EQ(v.glyphDiameterMm, kBlueNoiseDiameterFraction * 12.0);
  EXPECT_EQ(v.glyphMap.seed, 7u);
  EXPECT_NEAR(glyphSpacingMm(v), 12.0, 1e-9);
}

TEST(ViewControls, FunctionalWindowIsTheUsersOrTheRange) {
  render::RenderSettings v;
  EXPECT_EQ(functionalWindow(v, {0.0, 10.0}), (ValueWindow{0.0, 10.0}));
  setFunctionalWindow(v, 2.0, 5.0, {0.0, 10.0});
  EXPECT_EQ(functionalWindow(v, {0.0, 10.0}), (ValueWindow{2.0, 5.0}));
  // An empty window keeps a millionth of the range.
  setFunctionalWindow(v, 4.0, 3.0, {0.0, 10.0});
  EXPECT_DOUBLE_EQ(v.functionalWindow.low, 4.0);
  EXPECT_DOUBLE_EQ(v.functionalWindow.high, 4.0 + 1e-5);
}

}  // namespace
}  // namespace mvw::viewer
