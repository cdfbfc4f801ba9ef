// The framing sphere and the default step: the renderer, the validator and the GL tests all
// frame through these, so their answers are pinned here against hand-computed geometry.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "mvw/core/Volume.h"
#include "mvw/render/Framing.h"

namespace mvw::render {
namespace {

TEST(Framing, SphereIsTheVoxelBoxCentreAndHalfItsDiagonal) {
  // 10 x 20 x 5 voxels of 1 x 0.5 x 3 mm: a 10 x 10 x 15 mm box whose first voxel centre is at
  // the origin, so its faces lie half a voxel further out.
  const Volume v({10, 20, 5}, 1, ScalarType::UInt8,
                 makeWorldFromIndex({0, 0, 0}, {1, 0.5, 3}, glm::dmat3(1.0)));
  const FramingSphere f = framingSphere(v);
  EXPECT_NEAR(f.centre.x, 4.5, 1e-12);
  EXPECT_NEAR(f.centre.y, 4.75, 1e-12);
  EXPECT_NEAR(f.centre.z, 6.0, 1e-12);
  EXPECT_NEAR(f.radius, 0.5 * std::sqrt(10.0 * 10.0 + 10.0 * 10.0 + 15.0 * 15.0), 1e-12);
  EXPECT_DOUBLE_EQ(defaultStepMm(v), 0.25);
}

TEST(Framing, SphereFollowsTheDirectionMatrix) {
  // The same box stored flipped along i and j (RAS order): the same sphere in the world.
  const Volume lps({10, 20, 5}, 1, ScalarType::UInt8,
                   makeWorldFromIndex({0, 0, 0}, {1, 0.5, 3}, glm::dmat3(1.0)));
  const Volume ras({10, 20, 5}, 1, ScalarType::UInt8,
                   makeWorldFromIndex({9, 9.5, 0}, {1, 0.5, 3},
                                      glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0),
                                                 glm::dvec3(0, 0, 1))));
  const FramingSphere a = framingSphere(lps), b = framingSphere(ras);
  EXPECT_NEAR(glm::length(a.centre - b.centre), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.radius, b.radius);
  EXPECT_DOUBLE_EQ(defaultStepMm(ras), 0.25);
}

}  // namespace
}  // namespace mvw::render
