// Slice placement (io SliceGeometry: uneven and missing slices, gantry tilt), on synthetic
// stacks whose answers are known analytically. The real-data counterparts are in
// tests/real-data/dicom_geometry_test.cpp.
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "IoTestUtil.h"
#include "SliceGeometry.h"
#include "mvw/core/Error.h"

namespace {

using mvw::io::detail::placeSlices;
using mvw::test::hasNote;

constexpr std::size_t kNoLimit = std::size_t{1} << 34;

// A stack as vtk-dicom hands it over: nx x ny x positions.size(), columns u*su, v*sv and the
// normal n times the distance of the first two slices along it.
mvw::Volume stackOf(int nx, int ny, const std::vector<glm::dvec3>& positions, glm::dvec3 u,
                    glm::dvec3 v, double su, double sv, mvw::ScalarType type) {
  glm::dmat4 w(1.0);
  w[0] = glm::dvec4(u * su, 0);
  w[1] = glm::dvec4(v * sv, 0);
  const glm::dvec3 n = glm::cross(u, v);
  w[2] = glm::dvec4(n * (positions.size() > 1 ? glm::dot(positions[1] - positions[0], n) : 1.0), 0);
  w[3] = glm::dvec4(positions[0], 1);
  return mvw::Volume({nx, ny, static_cast<int>(positions.size())}, 1, type, w);
}

TEST(SlicePlacement, RegularStackIsKeptBitForBit) {
  std::vector<glm::dvec3> p;
  for (int k = 0; k < 5; ++k) p.push_back({-10.0, 4.0, 2.5 * k + 1e-7 * (k % 2)});
  mvw::Volume s = stackOf(3, 2, p, {1, 0, 0}, {0, 1, 0}, 0.7, 0.8, mvw::ScalarType::Int16);
  for (int k = 0; k < 5; ++k) s.setValue(1, 1, k, 0, 100 + k);
  const std::vector<std::byte> before(s.data(), s.data() + s.byteSize());
  const glm::dmat4 matrix = s.worldFromIndex();
  const mvw::Volume out = placeSlices(s, p, 0.0, kNoLimit, "stack");
  EXPECT_EQ(out.dimensions(), glm::ivec3(3, 2, 5));
  EXPECT_EQ(out.worldFromIndex(), matrix);
  EXPECT_EQ(std::memcmp(out.data(), before.data(), before.size()), 0);
  ASSERT_TRUE(out.metadata().sliceSpacing.has_value());
  EXPECT_TRUE(out.metadata().sliceSpacing->regular);
  EXPECT_FALSE(out.metadata().sliceSpacing->resampled);
  EXPECT_TRUE(out.metadata().notes.empty());
}

// vtk-dicom without a usable ImageOrientationPatient stacks slices 1 mm apart from the
// origin: the positions place them, with a note, the pixels untouched.
TEST(SlicePlacement, ReaderMatrixThatDisagreesWithThePositionsIsReplaced) {
  std::vector<glm::dvec3> p;
  for (int k = 0; k < 4; ++k) p.push_back({-10.0, 4.0, 30.0 + 1.5 * k});
  mvw::Volume s = stackOf(3, 2, p, {1, 0, 0}, {0, 1, 0}, 0.7, 0.8, mvw::ScalarType::Int16);
  glm::dmat4 w = s.worldFromIndex();
  w[2] = glm::dvec4(0, 0, 1, 0);
  w[3] = glm::dvec4(0, 0, 0, 1);
  s.setWorldFromIndex(w);
  for (int k = 0; k < 4; ++k) s.setValue(1, 1, k, 0, 100 + k);
  const std::vector<std::byte> before(s.data(), s.data() + s.byteSize());
  const mvw::Volume out = placeSlices(s, p, 0.0, kNoLimit, "stack");
  EXPECT_EQ(out.dimensions(), glm::ivec3(3, 2, 4));
  EXPECT_EQ(std::memcmp(out.data(), before.data(), before.size()), 0);
  for (int k = 0; k < 4; ++k)
    EXPECT_LT(glm::length(out.worldFromIndexPoint({0, 0, k}) - p[static_cast<std::size_t>(k)]),
              1e-9);
  EXPECT_TRUE(hasNote(out, "slices placed by their positions, 1.500 mm apart"));
}

TEST(SlicePlacement, MissingSliceIsInterpolatedAndTheOthersKeptExactly) {
  // Acquired at z = 0, 1, 3, 4 (the one at 2 is missing): the grid is 1 mm, five planes.
  const std::vector<glm::dvec3> p = {{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {0, 0, 4}};
  mvw::Volume s = stackOf(2, 2, p, {1, 0, 0}, {0, 1, 0}, 1.0, 1.0, mvw::ScalarType::Int16);
  const int value[4] = {10, 17, 31, 50};
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) s.setValue(i, j, k, 0, value[k] + i + 2 * j);
  const mvw::Volume out = placeSlices(s, p, 0.0, kNoLimit, "stack");
  ASSERT_EQ(out.dimensions(), glm::ivec3(2, 2, 5));
  EXPECT_NEAR(out.spacing().z, 1.0, 1e-12);
  EXPECT_EQ(out.origin(), glm::dvec3(0.0));
  const int expect[5] = {10, 17, 24, 31, 50};  // 24 = (17 + 31) / 2
  for (int m = 0; m < 5; ++m)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) EXPECT_EQ(out.value(i, j, m), expect[m] + i + 2 * j) << m;
  EXPECT_TRUE(out.metadata().sliceSpacing->resampled);
  EXPECT_FALSE(out.metadata().sliceSpacing->regular);
  EXPECT_TRUE(hasNote(out,
                      "gap of 2.000 mm after slice 2 of 4 (at LPS 0.0, 0.0, 1.0 mm): about "
                      "1 slice missing"));
  EXPECT_TRUE(hasNote(out, "resampled along the normal onto 1.000 mm"));
}

// A linear function of world position is reproduced exactly by linear interpolation along the
// normal and bilinear in-plane: every grid voxel inside the slices' footprints must equal it.
double linear(const glm::dvec3& x) { return 3.0 + 0.5 * x.x - 0.25 * x.y + 0.125 * x.z; }

TEST(SlicePlacement, GantryTiltIsResampledOntoAnOrthogonalGrid) {
  // Oblique rows and columns, slices 2 mm apart along the normal, each shifted 0.6 mm along
  // the column direction (a 16.7 degree tilt) and unevenly spaced after the fourth.
  const glm::dvec3 u = glm::normalize(glm::dvec3(1, 0.2, 0));
  const glm::dvec3 v = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), u));
  const glm::dvec3 n = glm::cross(u, v);
  const double su = 0.5, sv = 0.75;
  std::vector<glm::dvec3> p;
  const double along[6] = {0, 2, 4, 6, 7, 11};
  for (double a : along) p.push_back(glm::dvec3(5, -3, 2) + n * a + v * (0.3 * a));
  mvw::Volume s = stackOf(20, 16, p, u, v, su, sv, mvw::ScalarType::Float32);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 20; ++i)
        s.setValue(i, j, k, 0, linear(p[k] + u * (su * i) + v * (sv * j)));
  const mvw::Volume out = placeSlices(s, p, 0.0, kNoLimit, "stack");
  EXPECT_TRUE(hasNote(out, "gantry tilt 16.7 degrees"));
  const glm::dmat3 d = out.direction();
  EXPECT_NEAR(glm::length(d[0] - u), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(d[1] - v), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(d[2] - n), 0.0, 1e-12);
  EXPECT_NEAR(out.spacing().z, 1.0, 1e-12);                 // the smallest distance
  EXPECT_EQ(out.dimensions(), glm::ivec3(20, 16 + 5, 12));  // 3.3 mm shift = 4.4 rows
  int checked = 0;
  for (int m = 0; m < out.dimensions().z; ++m)
    for (int j = 0; j < out.dimensions().y; ++j)
      for (int i = 0; i < out.dimensions().x; ++i) {
        const glm::dvec3 x = out.worldFromIndexPoint({i, j, m});
        // Inside both bracketing slices' footprints (the shift is 0.3 mm per mm of normal).
        const double a = glm::dot(x - p[0], n);
        double lo = 0, hi = 11;
        for (double c : along) {
          if (c <= a + 1e-9) lo = c;
          if (c >= a - 1e-9 && c < hi) hi = c;
        }
        const double rowLo = (glm::dot(x - p[0], v) - 0.3 * lo) / sv;
        const double rowHi = (glm::dot(x - p[0], v) - 0.3 * hi) / sv;
        if (rowLo < 0 || rowLo > 15 || rowHi < 0 || rowHi > 15) continue;
        ++checked;
        EXPECT_NEAR(out.value(i, j, m), linear(x), 2e-5) << i << " " << j << " " << m;
      }
  EXPECT_GT(checked, 20 * 8 * 12);
}

TEST(SlicePlacement, ConfiguredSpacingAndTheMemoryLimitApply) {
  const std::vector<glm::dvec3> p = {{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {0, 0, 4}};
  const mvw::Volume s = stackOf(8, 8, p, {1, 0, 0}, {0, 1, 0}, 1, 1, mvw::ScalarType::UInt8);
  const mvw::Volume half = placeSlices(s, p, 0.5, kNoLimit, "stack");
  EXPECT_EQ(half.dimensions().z, 9);
  EXPECT_NEAR(half.spacing().z, 0.5, 1e-12);
  EXPECT_TRUE(hasNote(half, "onto 0.500 mm (as configured)"));
  EXPECT_THROW(placeSlices(s, p, 0.5, 8 * 8 * 8, "stack"), mvw::InputError);
  EXPECT_THROW(placeSlices(s, p, 1e-9, kNoLimit, "stack"), mvw::InputError);
}

TEST(SlicePlacement, NearDuplicateSlicesDoNotMultiplyTheVolume) {
  // One slice pair 0.01 mm apart among 5 mm slices: the grid is capped at a quarter of the
  // median distance, not 0.01 mm.
  const std::vector<glm::dvec3> p = {{0, 0, 0}, {0, 0, 5}, {0, 0, 5.01}, {0, 0, 10}, {0, 0, 15}};
  const mvw::Volume s = stackOf(4, 4, p, {1, 0, 0}, {0, 1, 0}, 1, 1, mvw::ScalarType::Int16);
  const mvw::Volume out = placeSlices(s, p, 0.0, kNoLimit, "stack");
  EXPECT_EQ(out.dimensions().z, 13);
  EXPECT_NEAR(out.spacing().z, 1.25, 1e-12);
  EXPECT_TRUE(hasNote(out, "capped at a quarter of the median"));
}

}  // namespace
