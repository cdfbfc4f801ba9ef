// The study loader (study StudyLoader) on the fetched nipy fMRI: a 4D functional volume
// contributes its mean or the chosen frame, with a note.
#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::study {
namespace {

// A study's 4D functional volume (the nipy fMRI: 20 frames) becomes one 3D volume with a note:
// the mean by default, or the frame the config names; a frame it lacks is bad input.
TEST(StudyLoader, A4DFunctionalVolumeContributesTheMeanOrTheChosenFrame) {
  const auto path = test::sampleData("nipy/functional.nii.gz");
  const Volume all = io::readVolume(path);
  ASSERT_EQ(all.components(), 20);
  config::VolumeSource source{path, "", "", "", config::defaultFrame(config::FunctionalKind::Fmri)};
  const Volume mean = readSource(source, {}, {});
  EXPECT_EQ(mean.components(), 1);
  EXPECT_EQ(mean.dimensions(), all.dimensions());
  EXPECT_EQ(mean.worldFromIndex(), all.worldFromIndex());
  double sum = 0.0;
  for (int f = 0; f < 20; ++f) sum += all.value(8, 10, 1, f);
  EXPECT_NEAR(mean.value(8, 10, 1), sum / 20, 1e-3);
  EXPECT_NE(mean.metadata().notes.back().find("mean over all frames"), std::string::npos);
  source.frame = FrameChoice{false, 7};
  const Volume f7 = readSource(source, {}, {});
  EXPECT_EQ(f7.value(8, 10, 1), all.value(8, 10, 1, 7));
  EXPECT_EQ(f7.metadata().notes.back(), "4D volume of 20 frames: frame 7 is used");
  source.frame = FrameChoice{false, 20};
  try {
    readSource(source, {}, {});
    FAIL() << "frame 20 of 20 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.problem().find("20 frames (0 .. 19)"), std::string::npos) << e.what();
  }
  // No frame given (the anatomy's default): frame 0, said in a note.
  source.frame.reset();
  EXPECT_EQ(readSource(source, {}, {}).metadata().notes.back(),
            "4D volume of 20 frames: frame 0 is used");
}

}  // namespace
}  // namespace mvw::study
