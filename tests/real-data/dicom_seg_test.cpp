// The real DICOM SEG beside the whole-body PET (../shared/data/pet-fdg-wholebody): two segments
// on the PET's frame of reference, read as masks in world coordinates; every segment frame lands
// on a PET slice; bad copies (truncated pixel data, a lying frame count) are refused.
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>

#include "SharedData.h"
#include "mvw/core/Error.h"
#include "mvw/io/DicomSeg.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/RoiStatistics.h"

namespace {

namespace fs = std::filesystem;

TEST(RealSeg, ReadsBothSegmentsOnThePetGrid) {
  MVW_REQUIRE_SHARED_DATA("pet-fdg-wholebody");
  const fs::path segFile = sharedPath / "tumour-segmentation.dcm";
  ASSERT_TRUE(mvw::io::isDicomSegmentation(segFile));
  EXPECT_FALSE(mvw::io::isDicomSegmentation(sharedPath / "PET_000000.dcm"));
  const mvw::io::Segmentation seg = mvw::io::readDicomSegmentation(segFile);
  EXPECT_EQ(seg.type, "BINARY");
  EXPECT_EQ(seg.frames, 13);
  ASSERT_EQ(seg.segments.size(), 2u);
  EXPECT_EQ(seg.segments[0].number, 1);
  EXPECT_EQ(seg.segments[0].label, "Neoplasm, Primary");
  EXPECT_EQ(seg.segments[0].frames, 4);
  EXPECT_EQ(seg.segments[1].label, "Neoplasm, Secondary");
  EXPECT_EQ(seg.segments[1].frames, 9);
  ASSERT_TRUE(seg.segments[0].rgb && seg.segments[1].rgb);
  EXPECT_EQ(seg.masks.dimensions().x, 128);
  EXPECT_EQ(seg.masks.components(), 2);
  EXPECT_NEAR(seg.masks.spacing().z, 3.375, 1e-6);

  mvw::io::ReadOptions options;
  options.series = "PET WB";
  const mvw::Volume pet = mvw::io::readVolume(sharedPath, options);
  EXPECT_EQ(pet.metadata().frameOfReferenceUid, seg.frameOfReferenceUid);
  const auto placed = mvw::study::placeSegmentation(pet, seg);
  EXPECT_TRUE(placed.gridsCoincide) << placed.note;
  // Every set SEG voxel lands on one PET voxel (the grids coincide), so the counts agree.
  for (int s = 0; s < 2; ++s) {
    std::size_t set = 0;
    const glm::ivec3 d = seg.masks.dimensions();
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) set += seg.masks.value(i, j, k, s) != 0;
    EXPECT_GT(set, 0u);
    EXPECT_EQ(placed.labels[static_cast<std::size_t>(s)].voxels.size(), set);
  }

  // Through the generic reader: a label volume of segment numbers, described in the notes.
  const mvw::Volume labels = mvw::io::readVolume(segFile);
  EXPECT_EQ(labels.metadata().modality, "SEG");
  EXPECT_EQ(labels.valueRange().second, 2.0);
  bool named = false;
  for (const auto& n : labels.metadata().notes) named |= n.find("Neoplasm, Secondary") != n.npos;
  EXPECT_TRUE(named);
}

TEST(RealSeg, BadCopiesAreRefused) {
  MVW_REQUIRE_SHARED_DATA("pet-fdg-wholebody");
  std::ifstream in(sharedPath / "tumour-segmentation.dcm", std::ios::binary);
  const std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
  const fs::path dir = fs::path(MVW_TEST_OUTPUT_DIR) / "seg";
  fs::create_directories(dir);
  // Truncated in the pixel data (a temporary copy in the build tree, never in the repository).
  const fs::path truncated = dir / "truncated.dcm";
  std::ofstream(truncated, std::ios::binary).write(bytes.data(), bytes.size() - 4000);
  try {
    mvw::io::readVolume(truncated);
    ADD_FAILURE() << "truncated SEG read";
  } catch (const mvw::InputError& e) {
    EXPECT_EQ(e.file(), truncated);
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  fs::remove(truncated);
}

}  // namespace
