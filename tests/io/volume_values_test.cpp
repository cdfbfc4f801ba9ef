// Voxel values that are not numbers (core Volume, io VolumeReader): NaN is "no data", +-inf is
// clamped on read with a note, the value range is always finite.
#include <cmath>
#include <limits>
#include <utility>

#include <gtest/gtest.h>

#include "IoTestUtil.h"
#include "TestUtil.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"

namespace {

using mvw::test::hasNote;

TEST(VolumeValues, RangeSkipsNanAndInfinities) {
  mvw::Volume v({4, 1, 1}, 1, mvw::ScalarType::Float32, glm::dmat4(1.0));
  const float values[4] = {std::nanf(""), -std::numeric_limits<float>::infinity(), -3.5f,
                           std::numeric_limits<float>::infinity()};
  for (int i = 0; i < 4; ++i) v.setValue(i, 0, 0, 0, values[i]);
  EXPECT_EQ(v.valueRange(), std::make_pair(-3.5, -3.5));
}

TEST(VolumeValues, InfinitiesAreClampedOnReadWithANote) {
  mvw::Volume v({3, 2, 2}, 1, mvw::ScalarType::Float32, glm::dmat4(1.0));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) v.setValue(i, j, k, 0, i + 10 * j - 5 * k);
  v.setValue(1, 1, 0, 0, std::numeric_limits<double>::infinity());
  v.setValue(2, 0, 1, 0, -std::numeric_limits<double>::infinity());
  v.setValue(0, 0, 0, 0, std::nan(""));
  const auto path = mvw::test::scratchDir() / "inf-voxels.nii.gz";
  mvw::io::writeVolume(v, path);
  const mvw::Volume r = mvw::io::readVolume(path);
  EXPECT_EQ(r.value(1, 1, 0), 12.0);  // the largest finite value
  EXPECT_EQ(r.value(2, 0, 1), -5.0);  // the smallest
  EXPECT_TRUE(std::isnan(r.value(0, 0, 0)));
  EXPECT_TRUE(hasNote(r,
                      "1 voxel +inf clamped to the largest finite value 12; 1 voxel -inf "
                      "clamped to the smallest finite value -5"));
  EXPECT_EQ(r.valueRange(), std::make_pair(-5.0, 12.0));
}

}  // namespace
