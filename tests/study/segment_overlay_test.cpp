// A study's "segmentation": the config key (read, written back, refused when its file is
// missing), a label volume read as per-label masks for the MPR outlines, and where the overlay
// goes (with the functional volume's placement only on the same frame of reference).
#include <fstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/study/SegmentOverlay.h"

namespace mvw::study {
namespace {

namespace fs = std::filesystem;

TEST(SegmentOverlay, ConfigKeyReadsWritesAndRefusesAMissingFile) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "anat.nii") << "x";
  std::ofstream(dir / "seg.dcm") << "x";
  std::ofstream(dir / "study.json")
      << R"({"anatomical": {"path": "anat.nii"}, "segmentation": {"path": "seg.dcm"}})";
  const config::StudyConfig c = config::loadStudyConfig(dir / "study.json");
  ASSERT_TRUE(c.segmentation);
  EXPECT_EQ(c.segmentation->path, dir / "seg.dcm");
  config::writeStudyConfig(c, dir / "again.json");
  const config::StudyConfig back = config::loadStudyConfig(dir / "again.json");
  ASSERT_TRUE(back.segmentation);
  EXPECT_EQ(back.segmentation->path, c.segmentation->path);
  std::ofstream(dir / "bad.json")
      << R"({"anatomical": {"path": "anat.nii"}, "segmentation": {"path": "nope.dcm"}})";
  EXPECT_THROW(config::loadStudyConfig(dir / "bad.json"), InputError);
}

TEST(SegmentOverlay, LabelVolumeBecomesOneMaskPerLabel) {
  const fs::path dir = test::scratchDir();
  Volume labels({4, 3, 2}, 1, ScalarType::UInt8,
                makeWorldFromIndex({1, 2, 3}, {2, 2, 2}, glm::dmat3(1.0)));
  labels.setValue(0, 0, 0, 0, 5);
  labels.setValue(1, 0, 0, 0, 5);
  labels.setValue(3, 2, 1, 0, 9);
  io::writeVolume(labels, dir / "labels.nii.gz");
  const SegmentOverlay o = readSegmentOverlay({dir / "labels.nii.gz", ""}, {}, {});
  EXPECT_EQ(o.numbers, (std::vector<int>{5, 9}));
  EXPECT_EQ(o.names, (std::vector<std::string>{"label 5", "label 9"}));
  ASSERT_EQ(o.colours.size(), 2u);
  EXPECT_NE(o.colours[0], o.colours[1]);
  ASSERT_EQ(o.masks.components(), 2);
  // Counted per mask and located by world position (the NIfTI round trip may reorder indices).
  int count[2] = {0, 0};
  glm::dvec3 nine{0.0};
  const glm::ivec3 d = o.masks.dimensions();
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i)
        for (int c = 0; c < 2; ++c)
          if (o.masks.value(i, j, k, c) == 1.0) {
            ++count[c];
            if (c == 1) nine = o.masks.worldFromIndexPoint({i, j, k});
          }
  EXPECT_EQ(count[0], 2);
  EXPECT_EQ(count[1], 1);
  EXPECT_NEAR(glm::length(nine - glm::dvec3(7, 6, 5)), 0.0, 1e-6);

  // Not a label map: refused naming the file.
  Volume values = labels.converted(ScalarType::Float32, 0.5);
  io::writeVolume(values, dir / "values.nii.gz");
  EXPECT_THROW(readSegmentOverlay({dir / "values.nii.gz", ""}, {}, {}), InputError);
}

TEST(SegmentOverlay, FollowsTheFunctionalOnlyOnItsFrameOfReference) {
  SegmentOverlay o;
  o.masks = Volume({1, 1, 1}, 1, ScalarType::UInt8, glm::dmat4(1.0));
  Volume pet({1, 1, 1}, 1, ScalarType::Float32, glm::dmat4(1.0));
  const glm::dmat4 moved = glm::translate(glm::dmat4(1.0), glm::dvec3(3, 4, 5));
  EXPECT_EQ(anatomicalFromSegmentation(o, &pet, moved), glm::dmat4(1.0));  // none stated
  o.masks.metadata().frameOfReferenceUid = "1.2";
  pet.metadata().frameOfReferenceUid = "1.2";
  EXPECT_EQ(anatomicalFromSegmentation(o, &pet, moved), moved);
  pet.metadata().frameOfReferenceUid = "1.3";
  EXPECT_EQ(anatomicalFromSegmentation(o, &pet, moved), glm::dmat4(1.0));
  EXPECT_EQ(anatomicalFromSegmentation(o, nullptr, moved), glm::dmat4(1.0));
}

}  // namespace
}  // namespace mvw::study
