// Orientation codes (core), as `mvw info` and the captions show them: each axis named by the
// side it points toward, by its dominant direction, and oblique when tilted.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "mvw/core/Orientation.h"

namespace mvw {
namespace {

TEST(Orientation, CodesNameTheSideEachAxisPointsToward) {
  EXPECT_EQ(orientationCode(glm::dmat3(1.0)), "LPS");
  EXPECT_EQ(
      orientationCode(glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1))),
      "RAS");
  // Sagittal slices: columns toward P, rows toward I (downward), slices toward L.
  EXPECT_EQ(
      orientationCode(glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0))),
      "PIL");
  // Coronal with a 10 degree tilt still reads by its dominant axes, and counts as oblique.
  const glm::dmat3 tilted =
      glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(10.0), glm::dvec3(1, 0, 0))) *
      glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
  EXPECT_EQ(orientationCode(tilted), "LIP");
  EXPECT_TRUE(isOblique(tilted));
  EXPECT_FALSE(isOblique(glm::dmat3(1.0)));
}

}  // namespace
}  // namespace mvw
