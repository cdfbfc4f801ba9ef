// resample() onto a fixed grid (issue 3), which every fused view and `mvw register` rely on.
// Geometry is checked analytically: a linear ramp survives trilinear resampling exactly, a
// shifted cube moves by whole voxels; a label map gains no new labels.
#include <cstdint>
#include <set>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "mvw/resampling/Resample.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {
namespace {

// A volume whose value is a linear function of the world position: trilinear interpolation
// reproduces it exactly, so every resampled voxel can be checked against the formula.
double ramp(const glm::dvec3& world) { return 2.0 * world.x + 3.0 * world.y - world.z + 100.0; }

Volume rampVolume() {
  const glm::dmat3 dir(glm::rotate(glm::dmat4(1.0), 0.5, glm::normalize(glm::dvec3(1, 2, -1))));
  Volume v({23, 19, 17}, 1, ScalarType::Float64,
           makeWorldFromIndex({-30.0, -20.0, -15.0}, {2.5, 3.0, 3.5}, dir));
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 19; ++j)
      for (int i = 0; i < 23; ++i) v.setValue(i, j, k, 0, ramp(v.worldFromIndexPoint({i, j, k})));
  return v;
}

TEST(Resample, OutputLiesOnTheFixedGridAndHonoursDirectionsAndTransform) {
  const Volume moving = rampVolume();
  // Oblique, left-handed fixed grid with other spacings: every geometry path is exercised.
  glm::dmat3 dir(glm::rotate(glm::dmat4(1.0), -0.3, glm::normalize(glm::dvec3(0.2, 1, 0.4))));
  dir[2] = -dir[2];
  // Centred on the moving volume and larger than it: both inside and outside voxels.
  const glm::ivec3 dims(31, 27, 21);
  const glm::dvec3 spacing(2.3, 2.6, 3.1);
  const glm::dvec3 middle = moving.worldFromIndexPoint(glm::dvec3(moving.dimensions() - 1) * 0.5);
  const Grid grid{dims, makeWorldFromIndex(middle - dir * (spacing * glm::dvec3(dims - 1) * 0.5),
                                           spacing, dir)};
  const Transform fixedFromMoving(rigidMatrix({{0.1, -0.15, 0.2}, {4.0, -6.0, 2.5}}, {0, 0, 0}));
  ResampleOptions options;
  options.background = -12345.0;
  const Volume out = resample(moving, grid, fixedFromMoving, options);

  ASSERT_EQ(out.dimensions(), grid.dimensions);
  EXPECT_EQ(out.worldFromIndex(), grid.worldFromIndex);  // exactly, not approximately
  EXPECT_EQ(out.scalarType(), ScalarType::Float64);
  const glm::dmat4 movingIndexFromWorld = glm::inverse(moving.worldFromIndex());
  int inside = 0, outside = 0;
  for (int k = 0; k < grid.dimensions.z; ++k)
    for (int j = 0; j < grid.dimensions.y; ++j)
      for (int i = 0; i < grid.dimensions.x; ++i) {
        const glm::dvec3 fixedWorld = out.worldFromIndexPoint({i, j, k});
        const glm::dvec3 movingWorld = fixedFromMoving.movingFromFixedPoint(fixedWorld);
        const glm::dvec3 idx(movingIndexFromWorld * glm::dvec4(movingWorld, 1.0));
        const glm::dvec3 hi = glm::dvec3(moving.dimensions()) - 1.0;
        const double margin = 0.45;  // away from the half-voxel border band
        if (glm::all(glm::greaterThan(idx, glm::dvec3(margin))) &&
            glm::all(glm::lessThan(idx, hi - margin))) {
          ++inside;
          // vtkImageReslice carries positions and weights partly in float (about 1e-6
          // relative here); a geometry error of 0.001 mm would already show as 0.004.
          ASSERT_NEAR(out.value(i, j, k), ramp(movingWorld), 1e-3) << i << "," << j << "," << k;
        } else if (glm::any(glm::lessThan(idx, glm::dvec3(-0.55))) ||
                   glm::any(glm::greaterThan(idx, hi + 0.55))) {
          ++outside;
          ASSERT_EQ(out.value(i, j, k), -12345.0);
        }
      }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

TEST(Resample, LargeOutputsAreFilledSlabBySlabWithoutSeams) {
  // 400 x 400 float64 slices (1.25 MiB each) come out of VTK a few slices at a time: every
  // slice, the slab borders and the short last slab included, must hold its own values.
  const Volume moving = rampVolume();
  const glm::dvec3 middle = moving.worldFromIndexPoint(glm::dvec3(moving.dimensions() - 1) * 0.5);
  const glm::ivec3 dims(400, 400, 20);
  const glm::dvec3 spacing(0.1, 0.1, 1.5);
  const Grid grid{dims, makeWorldFromIndex(middle - spacing * glm::dvec3(dims - 1) * 0.5, spacing,
                                           glm::dmat3(1.0))};
  const Transform t(rigidMatrix({{0.05, -0.1, 0.2}, {1.0, -2.0, 0.5}}, middle));
  const Volume out = resample(moving, grid, t);
  ASSERT_EQ(out.dimensions(), dims);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; j += 37)
      for (int i = 0; i < dims.x; i += 41)
        ASSERT_NEAR(out.value(i, j, k),
                    ramp(t.movingFromFixedPoint(out.worldFromIndexPoint({i, j, k}))), 1e-3)
            << i << "," << j << "," << k;
}

TEST(Resample, KnownShiftMovesABrightCubeByWholeVoxels) {
  const glm::dmat3 flip(glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1),
                        glm::dvec3(0, -1, 0));  // an LAI-like grid
  Volume moving({40, 36, 30}, 1, ScalarType::Int16,
                makeWorldFromIndex({50, -40, 30}, {2.0, 2.0, 2.0}, flip));
  for (int k = 10; k < 18; ++k)
    for (int j = 12; j < 20; ++j)
      for (int i = 14; i < 22; ++i) moving.setValue(i, j, k, 0, 1000);
  // The cube's content appears 6 mm further +x (left) and 4 mm further -z in the fixed world.
  const Transform fixedFromMoving(glm::translate(glm::dmat4(1.0), glm::dvec3(6.0, 0.0, -4.0)));
  const Grid grid = gridOf(moving);
  for (auto mode : {Interpolation::Nearest, Interpolation::Linear, Interpolation::Cubic}) {
    ResampleOptions options;
    options.interpolation = mode;
    const Volume out = resample(moving, grid, fixedFromMoving, options);
    // Each output voxel reads the moving volume 6 mm toward -x (+3 voxels along i, which
    // points to -x) and 4 mm toward +z (+2 voxels along j, which points to +z).
    for (int k = 0; k < 30; ++k)
      for (int j = 0; j < 36; ++j)
        for (int i = 0; i < 40; ++i) {
          const bool in = i >= 11 && i < 19 && j >= 10 && j < 18 && k >= 10 && k < 18;
          ASSERT_EQ(out.value(i, j, k), in ? 1000.0 : 0.0)
              << static_cast<int>(mode) << " " << i << "," << j << "," << k;
        }
  }
}

TEST(Resample, NearestNeighbourOnALabelMapCreatesNoNewLabels) {
  Volume labels({30, 28, 26}, 1, ScalarType::UInt8,
                makeWorldFromIndex({0, 0, 0}, {1.5, 1.5, 2.0}, glm::dmat3(1.0)));
  const std::set<double> allowed = {0, 3, 7, 200};
  for (int k = 0; k < 26; ++k)
    for (int j = 0; j < 28; ++j)
      for (int i = 0; i < 30; ++i)
        labels.setValue(i, j, k, 0,
                        (i / 6 + j / 7 + k / 5) % 2 ? (i < 15 ? 3 : 200) : (k < 13 ? 7 : 0));
  EXPECT_TRUE(looksLikeLabelMap(labels));
  EXPECT_EQ(chosenInterpolation(labels, {}), Interpolation::Nearest);
  const Transform t(rigidMatrix({{0.2, 0.1, -0.3}, {1.3, -2.1, 0.7}}, {22, 21, 26}));
  const Grid fine{{50, 45, 40}, makeWorldFromIndex({-2, -1, 1}, {0.9, 1.0, 1.3}, glm::dmat3(1.0))};
  auto valuesOf = [](const Volume& v) {
    std::set<double> s;
    for (std::size_t n = 0; n < v.voxelCount(); ++n)
      s.insert(static_cast<double>(v.dataAs<std::uint8_t>()[n]));
    return s;
  };
  const std::set<double> automatic = valuesOf(resample(labels, fine, t));
  for (double v : automatic) EXPECT_TRUE(allowed.count(v)) << "new label " << v;
  EXPECT_EQ(automatic, allowed);
  // The check can fail: linear interpolation of the same map does invent labels.
  ResampleOptions linear;
  linear.interpolation = Interpolation::Linear;
  const std::set<double> blended = valuesOf(resample(labels, fine, t, linear));
  EXPECT_GT(blended.size(), allowed.size());
  // A CT is not a label map.
  const Volume ramp16 = rampVolume().converted(ScalarType::Int16);
  EXPECT_FALSE(looksLikeLabelMap(ramp16));
}

TEST(Resample, AllComponentsOrTheFirst) {
  Volume v({9, 8, 7}, 3, ScalarType::Float32,
           makeWorldFromIndex({0, 0, 0}, {2, 2, 2}, glm::dmat3(1.0)));
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c) v.setValue(i, j, k, c, i + 10 * j + 100 * k + 1000 * c);
  const Transform shift(glm::translate(glm::dmat4(1.0), glm::dvec3(2.0, 0.0, 0.0)));
  const Volume all = resample(v, gridOf(v), shift);
  ResampleOptions first;
  first.allComponents = false;
  const Volume one = resample(v, gridOf(v), shift, first);
  ASSERT_EQ(all.components(), 3);
  ASSERT_EQ(one.components(), 1);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(all.value(4, 3, 2, c), 3 + 30 + 200 + 1000 * c);
  EXPECT_FLOAT_EQ(one.value(4, 3, 2, 0), 233);
}

}  // namespace
}  // namespace mvw::resampling
