// The rotating 3D view: the orbit's angles alone, and the keys and drags that start and stop it
// on the state's 3D camera.
#include "mvw/viewer/ViewerOrbit.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ViewerTestUtil.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::viewer {
namespace {

using ViewerOrbitTest = ViewerFixture;

// Spin steps a full turn in kFrames frames from where it started and comes back round; off
// gives no angle, and starting again starts from the first step.
TEST(ViewerOrbit, StepsFromTheStartingAzimuth) {
  ViewerOrbit orbit;
  EXPECT_EQ(orbit.mode(), Orbit::Off);
  EXPECT_EQ(orbit.advance(), std::nullopt);
  orbit.start(Orbit::Spin, 10.0);
  EXPECT_EQ(orbit.mode(), Orbit::Spin);
  ASSERT_TRUE(orbit.advance().has_value());
  for (int k = 2; k < ViewerOrbit::kFrames; ++k) orbit.advance();
  const std::optional<double> last = orbit.advance();  // the turn's first angle again
  ASSERT_TRUE(last.has_value());
  EXPECT_NEAR(std::remainder(*last - 10.0, 360.0), 0.0, 1e-9);
  orbit.start(Orbit::Spin, 10.0);
  EXPECT_NEAR(*orbit.advance(), 10.0 + 360.0 / ViewerOrbit::kFrames, 1e-9);
  orbit.start(Orbit::Off, 10.0);
  EXPECT_EQ(orbit.mode(), Orbit::Off);
  EXPECT_EQ(orbit.advance(), std::nullopt);
}

TEST_F(ViewerOrbitTest, SpinAndRockToggleAndTurnAboutTheLongAxis) {
  ViewerState state(study, pet, nullptr, sceneOf(pet));
  renderAll(state);
  state.drag(k3d, 0.1, 0.0, MouseButton::Left, false);  // azimuth 18
  const double start = state.view3d().camera.azimuthDeg;
  EXPECT_DOUBLE_EQ(start, 18.0);
  state.key('O', false);
  EXPECT_EQ(state.orbit().mode(), Orbit::Spin);
  renderAll(state);
  state.advanceOrbit();
  EXPECT_TRUE(state.needsRender(k3d));
  EXPECT_FALSE(state.needsRender(kAxial));  // the MPR panes stay as they are
  EXPECT_DOUBLE_EQ(state.view3d().camera.azimuthDeg, start + 360.0 / ViewerOrbit::kFrames);
  for (int k = 1; k < ViewerOrbit::kFrames / 2; ++k) state.advanceOrbit();
  EXPECT_NEAR(state.view3d().camera.azimuthDeg, start + 180.0, 1e-9);     // half way round
  EXPECT_EQ(state.view3d().camera.view, render::StandardView::Anterior);  // up stays S
  state.key('O', false);                                                  // off: stops where it is
  EXPECT_EQ(state.orbit().mode(), Orbit::Off);
  state.advanceOrbit();
  EXPECT_NEAR(state.view3d().camera.azimuthDeg, start + 180.0, 1e-9);

  // Rock: +-30 degrees about where it starts, a quarter of the way at the top of the swing.
  state.key('K', false);
  EXPECT_EQ(state.orbit().mode(), Orbit::Rock);
  for (int k = 0; k < ViewerOrbit::kFrames / 4; ++k) state.advanceOrbit();
  const double top = state.view3d().camera.azimuthDeg - (start + 180.0);
  EXPECT_NEAR(top,
              ViewerOrbit::kRockRangeDeg *
                  std::sin(2 * M_PI * (ViewerOrbit::kFrames / 4) / ViewerOrbit::kFrames),
              1e-9);
  EXPECT_GT(top, 29.0);
  state.key('O', false);  // the other toggle switches over
  EXPECT_EQ(state.orbit().mode(), Orbit::Spin);
  state.drag(k3d, 0.1, 0.0, MouseButton::Left, false);  // the reader takes the camera
  EXPECT_EQ(state.orbit().mode(), Orbit::Off);
  state.key('K', false);
  state.key('R', false);
  EXPECT_EQ(state.orbit().mode(), Orbit::Off);
  EXPECT_DOUBLE_EQ(state.view3d().camera.azimuthDeg, 0.0);
}

}  // namespace
}  // namespace mvw::viewer
