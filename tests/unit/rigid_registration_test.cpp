// registerRigid's refusals (issue 3): bad input is an InputError naming the file, and volumes
// that do not overlap start from their centroids; on synthetic blobs, without the sample data
// (the accuracy tests against a known truth are known_transform_test.cpp).
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "RegistrationTestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {
namespace {

TEST(RigidRegistration, BadInputIsRefusedWithTheFileName) {
  Volume good = blobs({0, 0, 0});
  good.metadata().sourcePath = "good.nii";
  Volume flat({20, 20, 1}, 1, ScalarType::Float32, glm::dmat4(1.0));
  flat.metadata().sourcePath = "flat.nii";
  Volume constant({20, 20, 20}, 1, ScalarType::Float32, glm::dmat4(1.0));
  constant.metadata().sourcePath = "constant.nii";
  Volume nan = blobs({0, 0, 0});
  nan.setValue(3, 4, 5, 0, std::nan(""));
  nan.metadata().sourcePath = "nan.nii";
  Volume far = blobs({0, 0, 0});
  far.setWorldFromIndex(glm::translate(glm::dmat4(1.0), glm::dvec3(1000, 0, 0)) *
                        far.worldFromIndex());
  far.metadata().sourcePath = "far.nii";
  RegistrationOptions world;
  world.initialisation = Initialisation::WorldCoordinates;
  auto expectRefused = [&](const Volume& fixed, const Volume& moving, const std::string& file) {
    try {
      registerRigid(fixed, moving, world);
      ADD_FAILURE() << file << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file().string(), file) << e.what();
    }
  };
  expectRefused(good, flat, "flat.nii");
  expectRefused(constant, good, "constant.nii");
  expectRefused(good, nan, "nan.nii");
  expectRefused(good, Volume(), "moving volume");
  expectRefused(good, far, "far.nii");
  // Automatic initialisation notices the missing overlap and starts from the centroids.
  const auto r = registerRigid(good, far);
  EXPECT_EQ(r.initialisation, Initialisation::CentreOfMass);
  EXPECT_LT(glm::length(r.transform.movingFromFixedPoint({0, 0, 0}) - glm::dvec3(1000, 0, 0)), 0.5);
}

}  // namespace
}  // namespace mvw::resampling
