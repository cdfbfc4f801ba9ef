// The 4D time frame (core Frame): one frame of a 4D volume or the voxel-wise mean, as a study's
// fMRI or dynamic PET contributes it, and the command line's spelling of the choice.
#include <string>

#include <gtest/gtest.h>

#include "mvw/core/Error.h"
#include "mvw/core/Frame.h"
#include "mvw/core/Volume.h"

namespace mvw {
namespace {

// What a 4D volume contributes (issue 14 item 8): one frame as stored, or the voxel-wise mean,
// each with a note; a frame the volume does not have is bad input naming the file.
TEST(Frame, OneFrameOrTheMeanWithANoteAndOutOfRangeIsBadInput) {
  Volume v({2, 1, 1}, 3, ScalarType::Int16, glm::dmat4(1.0));
  v.metadata().sourcePath = "fmri.nii.gz";
  for (int f = 0; f < 3; ++f) {
    v.setValue(0, 0, 0, f, 10 * (f + 1));  // 10 20 30
    v.setValue(1, 0, 0, f, -f);            // 0 -1 -2
  }
  const Volume f1 = selectFrame(v, {false, 1});
  EXPECT_EQ(f1.components(), 1);
  EXPECT_EQ(f1.scalarType(), ScalarType::Int16);
  EXPECT_EQ(f1.value(0, 0, 0), 20);
  EXPECT_EQ(f1.value(1, 0, 0), -1);
  ASSERT_FALSE(f1.metadata().notes.empty());
  EXPECT_EQ(f1.metadata().notes.back(), "4D volume of 3 frames: frame 1 is used");
  const Volume mean = selectFrame(v, {true, 0});
  EXPECT_EQ(mean.scalarType(), ScalarType::Float32);
  EXPECT_DOUBLE_EQ(mean.value(0, 0, 0), 20.0);
  EXPECT_DOUBLE_EQ(mean.value(1, 0, 0), -1.0);
  EXPECT_NE(mean.metadata().notes.back().find("mean over all frames"), std::string::npos);
  try {
    selectFrame(v, {false, 3});
    FAIL() << "frame 3 of 3 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "fmri.nii.gz");
    EXPECT_NE(std::string(e.what()).find("3 frames (0 .. 2)"), std::string::npos) << e.what();
  }
  // A 3D volume: frame 0 and the mean are the volume itself, frame 1 is refused.
  const Volume flat({2, 1, 1}, 1, ScalarType::UInt8, glm::dmat4(1.0));
  EXPECT_TRUE(selectFrame(flat, {false, 0}).metadata().notes.empty());
  EXPECT_EQ(selectFrame(flat, {true, 0}).scalarType(), ScalarType::UInt8);
  EXPECT_THROW(selectFrame(flat, {false, 1}), InputError);
  // The command line's spelling.
  EXPECT_TRUE(parseFrameChoice("mean")->mean);
  EXPECT_EQ(parseFrameChoice("12")->index, 12);
  for (const char* bad : {"", "-1", "1.5", "first", "0x1", "9999999999"})
    EXPECT_FALSE(parseFrameChoice(bad).has_value()) << bad;
}

}  // namespace
}  // namespace mvw
