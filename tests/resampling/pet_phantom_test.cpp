// `mvw phantom pet`'s volume (resampling::petPhantomVolume): the PetPhantom's PET under the
// rigid transform of the given degrees and millimetres about the CT's centre, on a small
// synthetic CT (a water ball in air) so that it runs in a moment.
#include <cstring>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include "mvw/resampling/PetPhantom.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {
namespace {

Volume ballCt() {
  Volume ct({24, 24, 20}, 1, ScalarType::Int16,
            makeWorldFromIndex({-46, -46, -38}, glm::dvec3(4.0), glm::dmat3(1.0)));
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i) {
        const glm::dvec3 w = ct.worldFromIndexPoint({i, j, k});
        ct.setValue(i, j, k, 0, glm::length(w) < 30.0 ? 40.0 : -1000.0);
      }
  return ct;
}

TEST(PetPhantom, TheVolumeOfPhantomPet) {
  const Volume ct = ballCt();
  const Volume pet = petPhantomVolume(ct, {10, 0, -5}, {3, -2, 1}, 7);
  const PetPhantom phantom(ct);
  RigidParameters p;
  p.angles = glm::radians(glm::dvec3(10, 0, -5));
  p.translation = {3, -2, 1};
  const Volume expected = phantom.pet(rigidMatrix(p, phantom.centre()), 7);
  EXPECT_EQ(pet.metadata().seriesDescription, "mvw PET-like phantom");
  ASSERT_EQ(pet.dimensions(), expected.dimensions());
  EXPECT_EQ(pet.worldFromIndex(), expected.worldFromIndex());
  ASSERT_EQ(pet.byteSize(), expected.byteSize());
  EXPECT_EQ(std::memcmp(pet.data(), expected.data(), pet.byteSize()), 0);
}

}  // namespace
}  // namespace mvw::resampling
