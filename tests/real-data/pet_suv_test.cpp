// The real whole-body FDG PET (../shared/data/pet-fdg-wholebody): SUVbw through the reader,
// checked against an independent computation from the DICOM tags (see the folder's README).
#include <gtest/gtest.h>

#include "SharedData.h"
#include "mvw/io/VolumeReader.h"

namespace {

TEST(RealPet, ReadsAsSuvbwWithTheIndependentMaximum) {
  MVW_REQUIRE_SHARED_DATA("pet-fdg-wholebody");
  mvw::io::ReadOptions options;
  options.series = "PET WB";  // the folder also holds the DICOM SEG
  const mvw::Volume pet = mvw::io::readVolume(sharedPath, options);
  EXPECT_EQ(pet.metadata().modality, "PT");
  EXPECT_EQ(pet.metadata().unit, "SUVbw");
  EXPECT_EQ(pet.dimensions(), glm::ivec3(128, 128, 299));
  const auto [lo, hi] = pet.valueRange();
  EXPECT_GE(lo, 0.0);
  EXPECT_NEAR(hi, 19.51, 0.01);
  EXPECT_NEAR(pet.spacing().z, 3.375, 1e-3);
}

}  // namespace
