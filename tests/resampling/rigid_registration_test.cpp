// registerRigid's refusals (issue 3): bad input is an InputError naming the file, and volumes
// that do not overlap start from their centroids; on synthetic blobs, without the sample data
// (the accuracy tests against a known truth are known_transform_test.cpp).
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "RegistrationTestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/resampling/PetPhantom.h"
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

// The coarse rotation search (RegistrationOptions::rotationSearchRangeDeg) on the blobs turned by
// 70 degrees about the feet-head axis: every grid rotation is scored, and the climb from the
// best candidates lands on the truth. (The accuracy of the search on the CT and a PET-like
// volume is KnownTransform.RotationSearchRecoversLargeRotations; this one runs in a moment,
// also under the sanitizers, which leave the KnownTransform suite to the release run.)
TEST(RigidRegistration, RotationSearchScoresEveryGridRotationAndFindsTheTurn) {
  // Two round blobs leave any turn about the line through them unseen: a third, off that line.
  auto threeBlobs = [] {
    Volume v = blobs({0, 0, 0});
    for (int k = 0; k < 36; ++k)
      for (int j = 0; j < 38; ++j)
        for (int i = 0; i < 40; ++i) {
          const glm::dvec3 w = v.worldFromIndexPoint({i, j, k}) - glm::dvec3(-12, 14, 10);
          v.setValue(i, j, k, 0, v.value(i, j, k) + 80.0 * std::exp(-glm::dot(w, w) / 80.0));
        }
    return v;
  };
  const Volume fixed = threeBlobs();
  Volume moving = threeBlobs();
  const glm::dvec3 centre = fixed.worldFromIndexPoint(glm::dvec3(fixed.dimensions() - 1) * 0.5);
  const glm::dmat4 truth =
      rigidMatrix({glm::dvec3(0, 0, 70) * (3.14159265358979 / 180), {}}, centre);
  moving.setWorldFromIndex(truth * moving.worldFromIndex());
  RegistrationOptions options;
  options.rotationSearchRangeDeg = 90.0;
  const auto r = registerRigid(fixed, moving, options);
  EXPECT_EQ(r.searchedRotations, 7 * 7 * 7);
  // Points 20 mm about the centre land within 1.5 voxels (3 mm) of the truth. (Which start the
  // search beats is KnownTransform's question, on the CT; on smooth blobs the climb from the
  // identity also gets there.)
  for (const glm::dvec3 p : {centre + glm::dvec3(20, 0, 0), centre + glm::dvec3(0, 20, 10)})
    EXPECT_LT(
        glm::length(r.transform.movingFromFixedPoint(p) - glm::dvec3(truth * glm::dvec4(p, 1))),
        3.0);
}

// The phantom's target registration error is the mean distance over its lattice (the CT's
// voxels above -300 HU on a sparse grid): 0 for the truth, the shift for a pure shift.
TEST(PetPhantom, TreIsTheMeanDistanceOverTheLatticeInsideTheHead) {
  Volume ct({40, 40, 30}, 1, ScalarType::Float32,
            makeWorldFromIndex({-40, -40, -30}, {2, 2, 2}, glm::dmat3(1.0)));
  for (int k = 0; k < 30; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) {
        const double r = glm::length(ct.worldFromIndexPoint({i, j, k}));
        // bone core, brain, a fatty layer (-500..-100 HU), air
        ct.setValue(i, j, k, 0, r < 8 ? 800.0 : r < 20 ? 40.0 : r < 26 ? -300.0 : -1000.0);
      }
  const PetPhantom phantom(ct);
  ASSERT_FALSE(phantom.lattice().empty());
  EXPECT_GT(phantom.uptake().value(20, 20, 15), 0.0);
  const glm::dmat4 shift = glm::translate(glm::dmat4(1.0), glm::dvec3(2, 0, 0));
  EXPECT_DOUBLE_EQ(phantom.meanTre(glm::dmat4(1.0), glm::dmat4(1.0)), 0.0);
  EXPECT_NEAR(phantom.meanTre(shift, glm::dmat4(1.0)), 2.0, 1e-9);
}

}  // namespace
}  // namespace mvw::resampling
