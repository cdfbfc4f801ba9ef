// The framing sphere and the default step: the renderer, the validator and the GL tests all
// frame through these, so their answers are pinned here against hand-computed geometry.
#include <cmath>
#include <tuple>

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

namespace mvw::render {
namespace {

// A crop box in patient terms reaches the ray caster as the texture box that holds the same
// world content, whatever the storage order (issue 14 item 3).
TEST(PatientCrop, FractionsAlongLpsBecomeTheTextureBoxOfTheSameWorldContent) {
  const glm::dvec3 lo(0.1, 0.2, 0.3), hi(0.6, 0.9, 0.55);
  // LPS order: texture box = LPS fractions.
  const Volume lps({10, 20, 5}, 1, ScalarType::UInt8,
                   makeWorldFromIndex({0, 0, 0}, {1, 0.5, 3}, glm::dmat3(1.0)));
  auto [a, b] = PatientCrop(lps).textureBox(lo, hi);
  EXPECT_EQ(a, lo);
  EXPECT_EQ(b, hi);
  // Slice axis reversed (k toward inferior): the superior end is texture 0.
  const Volume rev(
      {10, 20, 5}, 1, ScalarType::UInt8,
      makeWorldFromIndex({0, 0, 12}, {1, 0.5, 3}, glm::dmat3({1, 0, 0}, {0, 1, 0}, {0, 0, -1})));
  std::tie(a, b) = PatientCrop(rev).textureBox(lo, hi);
  EXPECT_NEAR(a.z, 1 - 0.55, 1e-12);
  EXPECT_NEAR(b.z, 1 - 0.3, 1e-12);
  EXPECT_NEAR(a.x, 0.1, 1e-12);
  // Permuted and flipped: i runs toward superior, j toward right, k toward posterior.
  const Volume perm(
      {5, 10, 20}, 1, ScalarType::UInt8,
      makeWorldFromIndex({9, 0, 0}, {3, 1, 0.5}, glm::dmat3({0, 0, 1}, {-1, 0, 0}, {0, 1, 0})));
  std::tie(a, b) = PatientCrop(perm).textureBox(lo, hi);
  EXPECT_NEAR(a.x, 0.3, 1e-12);  // i follows S
  EXPECT_NEAR(b.x, 0.55, 1e-12);
  EXPECT_NEAR(a.y, 1 - 0.6, 1e-12);  // j follows R: L fraction reversed
  EXPECT_NEAR(b.y, 1 - 0.1, 1e-12);
  EXPECT_NEAR(a.z, 0.2, 1e-12);  // k follows P
  EXPECT_NEAR(b.z, 0.9, 1e-12);
  // Every one of the three has the same world-aligned box, and the texture box is exact.
  for (const Volume* v : {&lps, &rev, &perm}) {
    const PatientCrop c(*v);
    EXPECT_TRUE(c.axisAligned());
    EXPECT_NEAR(c.boxMin().x, -0.5, 1e-9);
    EXPECT_NEAR(c.boxMax().x, 9.5, 1e-9);
    EXPECT_NEAR(c.boxMin().y, -0.25, 1e-9);
    EXPECT_NEAR(c.boxMax().y, 9.75, 1e-9);
    EXPECT_NEAR(c.boxMin().z, -1.5, 1e-9);
    EXPECT_NEAR(c.boxMax().z, 13.5, 1e-9);
  }
}

TEST(PatientCrop, AnObliqueVolumeIsCroppedByItsWorldAlignedBoxInMillimetres) {
  // 10 voxels of 1 mm along each axis, turned 90 degrees about S and then tilted: i runs
  // along P and S, so no texture box can hold an L, P, S crop and the world box does.
  const double c = std::sqrt(0.5);
  const Volume v(
      {10, 10, 10}, 1, ScalarType::UInt8,
      makeWorldFromIndex({0, 0, 0}, {1, 1, 1}, glm::dmat3({0, c, c}, {-1, 0, 0}, {0, -c, c})));
  const PatientCrop crop(v);
  EXPECT_FALSE(crop.axisAligned());
  const auto [lo, hi] = crop.worldBox({0.0, 0.0, 0.5}, {1.0, 1.0, 1.0});
  EXPECT_NEAR(lo.x, crop.boxMin().x, 1e-12);
  EXPECT_NEAR(hi.y, crop.boxMax().y, 1e-12);
  EXPECT_NEAR(lo.z, 0.5 * (crop.boxMin().z + crop.boxMax().z), 1e-12);
  EXPECT_NEAR(hi.z, crop.boxMax().z, 1e-12);
  // The box around the voxel box: i and k span 10 mm along P and S at 45 degrees each.
  EXPECT_NEAR(crop.boxMax().z - crop.boxMin().z, 2 * 10 * c, 1e-9);
}

TEST(PatientCrop, MillimetresAreFractionsOfTheWorldAlignedBox) {
  const Volume v(
      {10, 20, 5}, 1, ScalarType::UInt8,
      makeWorldFromIndex({0, 0, 12}, {1, 0.5, 3}, glm::dmat3({-1, 0, 0}, {0, 1, 0}, {0, 0, -1})));
  // Box: L -9.5 .. 0.5, P -0.25 .. 9.75, S -1.5 .. 13.5.
  const auto [a, b] = PatientCrop(v).fractionsFromMm({-4.5, -10, 0}, {0.5, 4.75, 6});
  EXPECT_NEAR(a.x, 0.5, 1e-12);
  EXPECT_NEAR(b.x, 1.0, 1e-12);
  EXPECT_NEAR(a.y, 0.0, 1e-12);  // clamped
  EXPECT_NEAR(b.y, 0.5, 1e-12);
  EXPECT_NEAR(a.z, 0.1, 1e-12);
  EXPECT_NEAR(b.z, 0.5, 1e-12);
}

}  // namespace
}  // namespace mvw::render
