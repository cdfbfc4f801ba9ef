// Volume (core), which every reader, renderer and statistic holds: the geometry read back from
// worldFromIndex, values and the value range with NaN, conversion with slope and intercept.
#include <limits>
#include <utility>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "mvw/core/Volume.h"

namespace mvw {
namespace {

TEST(Volume, GeometryComesBackFromWorldFromIndex) {
  const glm::dmat3 rot = glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(1, 2, 3)));
  const glm::dvec3 spacing(0.7, 1.1, 3.5), origin(-10.5, 20.25, 7.0);
  Volume v({7, 5, 3}, 1, ScalarType::Int16, makeWorldFromIndex(origin, spacing, rot));
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(v.spacing()[a], spacing[a], 1e-12);
    EXPECT_NEAR(v.origin()[a], origin[a], 1e-12);
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(v.direction()[a][b], rot[a][b], 1e-12);
  }
  // Voxel (2, 1, 1) lies at origin + 2*sx*i_dir + 1*sy*j_dir + 1*sz*k_dir.
  const glm::dvec3 expected = origin + rot[0] * (2 * 0.7) + rot[1] * 1.1 + rot[2] * 3.5;
  const glm::dvec3 got = v.worldFromIndexPoint({2, 1, 1});
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[a], expected[a], 1e-12);
  EXPECT_EQ(v.byteSize(), 7u * 5 * 3 * 2);
}

TEST(Volume, ValuesAndRangeIgnoreNaN) {
  Volume v({3, 2, 2}, 1, ScalarType::Float32, glm::dmat4(1.0));
  v.setValue(0, 0, 0, 0, -4.5);
  v.setValue(2, 1, 1, 0, 12.0);
  v.setValue(1, 1, 0, 0, std::numeric_limits<double>::quiet_NaN());
  const auto [lo, hi] = v.valueRange();
  EXPECT_EQ(lo, -4.5);
  EXPECT_EQ(hi, 12.0);
  EXPECT_EQ(v.value(2, 1, 1), 12.0);
}

// The range in the values' own type: integers (the extremes anywhere, the first voxel or the
// last) and float, whose infinities are left out like NaN.
TEST(Volume, RangeInEveryValueType) {
  Volume i16({4, 3, 2}, 1, ScalarType::Int16, glm::dmat4(1.0));
  i16.setValue(3, 2, 1, 0, -32768);
  i16.setValue(0, 0, 0, 0, 32767);
  EXPECT_EQ(i16.valueRange(), (std::pair<double, double>{-32768.0, 32767.0}));
  Volume u8({5, 1, 1}, 2, ScalarType::UInt8, glm::dmat4(1.0));
  for (int i = 0; i < 5; ++i) u8.setValue(i, 0, 0, 0, 7);
  u8.setValue(4, 0, 0, 1, 200);  // the second component counts too
  EXPECT_EQ(u8.valueRange(), (std::pair<double, double>{0.0, 200.0}));
  Volume f({3, 1, 1}, 1, ScalarType::Float32, glm::dmat4(1.0));
  f.setValue(0, 0, 0, 0, std::numeric_limits<double>::infinity());
  f.setValue(1, 0, 0, 0, -0.25);
  f.setValue(2, 0, 0, 0, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(f.valueRange(), (std::pair<double, double>{-0.25, -0.25}));
}

TEST(Volume, ConvertedAppliesSlopeAndIntercept) {
  Volume v({2, 1, 1}, 2, ScalarType::Int16, glm::dmat4(1.0));
  v.setValue(1, 0, 0, 1, 100);
  const Volume f = v.converted(ScalarType::Float32, 0.5, -1024);
  EXPECT_EQ(f.scalarType(), ScalarType::Float32);
  EXPECT_FLOAT_EQ(static_cast<float>(f.value(1, 0, 0, 1)), -974.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(f.value(0, 0, 0, 0)), -1024.0f);
}

}  // namespace
}  // namespace mvw
