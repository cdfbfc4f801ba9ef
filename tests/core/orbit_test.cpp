// mvw::Orbit: the azimuths of a rotating view's frames, spin and rock (mvw render --orbit and
// the viewer's rotating 3D pane turn through them).
#include "mvw/core/Orbit.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mvw {
namespace {

TEST(OrbitAzimuths, SpinTurnsAFullCircleAndRockSwingsOverItsRange) {
  Orbit orbit;
  orbit.frames = 8;
  const std::vector<double> spin = orbitAzimuths(orbit, 10);
  ASSERT_EQ(spin.size(), 8u);
  for (int k = 0; k < 8; ++k) EXPECT_DOUBLE_EQ(spin[k], 10 + 45.0 * k);
  orbit.mode = OrbitMode::Rock;
  orbit.rangeDeg = 30;
  const std::vector<double> rock = orbitAzimuths(orbit, 10);
  ASSERT_EQ(rock.size(), 8u);
  EXPECT_DOUBLE_EQ(rock[0], 10);
  EXPECT_NEAR(rock[2], 40, 1e-9);   // a quarter period: +range
  EXPECT_NEAR(rock[4], 10, 1e-9);   // half: back through the start
  EXPECT_NEAR(rock[6], -20, 1e-9);  // three quarters: -range
  EXPECT_NEAR(rock[1], 10 + 30 * std::sqrt(0.5), 1e-9);
  orbit.frames = 0;
  EXPECT_FALSE(orbit.on());
  EXPECT_TRUE(orbitAzimuths(orbit, 10).empty());
}

}  // namespace
}  // namespace mvw
