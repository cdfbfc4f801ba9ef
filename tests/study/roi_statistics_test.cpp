// ROI statistics (modules/study RoiStatistics) against analytic answers on synthetic volumes:
// a uniform sphere, a single hot voxel (SUVpeak = its value over the 123 voxels of the 1 cm^3
// sphere on a 2 mm grid), two-valued halves (SD), NaN voxels, thresholds, label placement and
// the bad-input refusals. Lattice counts: 4169 points of Z^3 within radius 10, 14147 within 15,
// 123 within 3 (the PERCIST sphere's 6.204 mm on a 2 mm grid), 1926 with x < 0 inside radius 10.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "mvw/core/Error.h"
#include "mvw/io/DicomSeg.h"
#include "mvw/study/RoiStatistics.h"

namespace mvw::study {
namespace {

// 41^3 voxels of `spacing` mm, stored mirrored in L and P (RAS-like index order), voxel
// (20,20,20) at world `centre`.
Volume cube(double spacing, const glm::dvec3& centre, const char* unit = "SUVbw") {
  const glm::dmat3 direction(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
  const glm::dvec3 origin = centre - direction * glm::dvec3(20.0 * spacing);
  Volume v({41, 41, 41}, 1, ScalarType::Float32,
           makeWorldFromIndex(origin, glm::dvec3(spacing), direction));
  v.metadata().unit = unit;
  v.metadata().sourcePath = "synthetic.nii";
  return v;
}

// Value `inside` at voxels within `radius` voxels of the centre voxel, `outside` elsewhere.
void fillSphere(Volume& v, double radius, double inside, double outside) {
  for (int k = 0; k < 41; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 41; ++i) {
        const double r2 =
            (i - 20.0) * (i - 20.0) + (j - 20.0) * (j - 20.0) + (k - 20.0) * (k - 20.0);
        v.setValue(i, j, k, 0, r2 <= radius * radius ? inside : outside);
      }
}

StatsOptions withPeak() {
  StatsOptions o;
  o.peak = true;
  return o;
}

TEST(RoiStatistics, UniformSphereExactly) {
  const glm::dvec3 c{12.5, -40.25, 101.0};
  Volume v = cube(1.0, c);
  fillSphere(v, 10.0, 5.0, 0.0);
  const VoxelList roi = sphereVoxels(v, {c, 10.0});
  StatsOptions o = withPeak();
  o.threshold = {Threshold::Kind::Absolute, 2.5};
  const RoiStats s = roiStatistics(v, roi, o);
  EXPECT_EQ(s.voxels, 4169u);
  EXPECT_DOUBLE_EQ(s.volumeMl, 4.169);
  EXPECT_EQ(s.max, 5.0);
  EXPECT_EQ(s.mean, 5.0);
  EXPECT_EQ(s.sd, 0.0);
  ASSERT_TRUE(s.peak);
  EXPECT_EQ(*s.peak, 5.0);
  EXPECT_EQ(s.unit, "SUVbw");
  EXPECT_EQ(s.metabolicVoxels, 4169u);
  EXPECT_DOUBLE_EQ(*s.metabolicVolumeMl, 4.169);

  // A larger ROI: the mean dilutes by the lattice counts, the max and the peak do not.
  const RoiStats big = roiStatistics(v, sphereVoxels(v, {c, 15.0}), withPeak());
  EXPECT_EQ(big.voxels, 14147u);
  EXPECT_NEAR(big.mean, 5.0 * 4169.0 / 14147.0, 1e-12);
  const double p = 4169.0 / 14147.0;
  EXPECT_NEAR(big.sd, 5.0 * std::sqrt(p * (1 - p)), 1e-12);
  EXPECT_EQ(*big.peak, 5.0);
  EXPECT_EQ(big.maxAt, v.worldFromIndexPoint({20, 20, 10}));  // the first hot voxel in storage
}

TEST(RoiStatistics, SingleHotVoxelGivesPeakOverThe1ccSphere) {
  const glm::dvec3 c{0.0, 0.0, 0.0};
  Volume v = cube(2.0, c);
  v.setValue(20, 20, 20, 0, 100.0);
  const RoiStats s = roiStatistics(v, sphereVoxels(v, {c, 9.0}), withPeak());
  ASSERT_TRUE(s.peak);
  EXPECT_NEAR(*s.peak, 100.0 / 123.0, 1e-12);
  EXPECT_EQ(s.peakSphereVoxels, 123u);
  // Every centre within the radius of the hot voxel ties; the first in storage order wins.
  EXPECT_LE(glm::length(s.peakAt - c), kPeakRadiusMm);
  EXPECT_EQ(s.peakAt, glm::dvec3(0.0, 0.0, -6.0));
  // The sphere's voxels may lie outside the ROI: a 1-voxel ROI beside the hot voxel still sees it.
  const RoiStats beside = roiStatistics(v, sphereVoxels(v, {{0.0, 0.0, 2.0}, 0.5}), withPeak());
  EXPECT_EQ(beside.voxels, 1u);
  EXPECT_EQ(beside.max, 0.0);
  EXPECT_NEAR(*beside.peak, 100.0 / 123.0, 1e-12);
  // Without peak the field stays empty (not SUV).
  EXPECT_FALSE(roiStatistics(v, sphereVoxels(v, {c, 9.0}), {}).peak);
}

TEST(RoiStatistics, TwoValuedHalvesSdAndRelativeThreshold) {
  const glm::dvec3 c{0.0, 0.0, 0.0};
  Volume v = cube(1.0, c);
  // World L (x) < 0 is index i > 20 (the L axis is mirrored): value 2 there, 8 elsewhere.
  for (int k = 0; k < 41; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 41; ++i) v.setValue(i, j, k, 0, i > 20 ? 2.0 : 8.0);
  StatsOptions o;
  o.threshold = {Threshold::Kind::FractionOfMax, 0.5};
  const RoiStats s = roiStatistics(v, sphereVoxels(v, {c, 10.0}), o);
  const double na = 1926, nb = 4169 - 1926;
  EXPECT_EQ(s.voxels, 4169u);
  EXPECT_NEAR(s.mean, (2 * na + 8 * nb) / 4169.0, 1e-12);
  EXPECT_NEAR(s.sd, 6.0 * std::sqrt(na * nb) / 4169.0, 1e-12);
  EXPECT_EQ(*s.thresholdValue, 4.0);
  EXPECT_EQ(s.metabolicVoxels, static_cast<std::size_t>(nb));
}

TEST(RoiStatistics, NanVoxelsAreNoData) {
  const glm::dvec3 c{0.0, 0.0, 0.0};
  Volume v = cube(1.0, c);
  fillSphere(v, 10.0, 3.0, 1.0);
  v.setValue(20, 20, 20, 0, std::numeric_limits<double>::quiet_NaN());
  v.setValue(21, 20, 20, 0, std::numeric_limits<double>::quiet_NaN());
  const RoiStats s = roiStatistics(v, sphereVoxels(v, {c, 10.0}), withPeak());
  EXPECT_EQ(s.voxels, 4167u);
  EXPECT_EQ(s.noData, 2u);
  EXPECT_EQ(s.mean, 3.0);
  EXPECT_EQ(s.sd, 0.0);
  EXPECT_EQ(*s.peak, 3.0);
}

TEST(RoiStatistics, BoxCountsVoxelCentres) {
  const glm::dvec3 c{5.0, 6.0, 7.0};
  Volume v = cube(1.0, c);
  fillSphere(v, 100.0, 1.0, 1.0);
  EXPECT_EQ(boxVoxels(v, {c - 3.5, c + 3.5}).size(), 343u);
  EXPECT_EQ(boxVoxels(v, {c - 3.0, c + 3.0}).size(), 343u);  // centres on the faces count
  // Partly outside: only the voxels of the volume.
  EXPECT_EQ(boxVoxels(v, {c + glm::dvec3(19.5, -0.2, -0.2), c + glm::dvec3(100, 0.2, 0.2)}).size(),
            1u);
}

TEST(RoiStatistics, BadRoisAreInputErrors) {
  const glm::dvec3 c{0.0, 0.0, 0.0};
  const Volume v = cube(1.0, c);
  EXPECT_THROW(sphereVoxels(v, {c, 0.0}), InputError);
  EXPECT_THROW(sphereVoxels(v, {c, -1.0}), InputError);
  EXPECT_THROW(sphereVoxels(v, {{0, 0, 500}, 10.0}), InputError);
  EXPECT_THROW(sphereVoxels(v, {{0, 0, 1e300}, 10.0}), InputError);  // no int overflow
  EXPECT_THROW(sphereVoxels(v, {{0, 0, -1e300}, 1e299}), InputError);
  EXPECT_THROW(boxVoxels(v, {{-1e300, 1e300, 0}, {1e300, 1e300, 1}}), InputError);
  EXPECT_THROW(sphereVoxels(v, {{0.5, 0.5, 0.5}, 0.1}), InputError);  // between centres
  EXPECT_THROW(boxVoxels(v, {{1, 0, 0}, {0, 1, 1}}), InputError);
  EXPECT_THROW(boxVoxels(v, {{100, 100, 100}, {200, 200, 200}}), InputError);
  try {
    sphereVoxels(v, {{0, 0, 500}, 10.0});
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "synthetic.nii");
    EXPECT_NE(std::string(e.what()).find("holds no voxel centre"), std::string::npos) << e.what();
  }
}

TEST(RoiStatistics, LabelVolumeOnACoarserGridByNearestNeighbour) {
  const glm::dvec3 c{0.0, 0.0, 0.0};
  const Volume v = cube(1.0, c);
  // Labels on a 2 mm LPS-ordered grid offset by half a voxel (no ties): label 3 near the centre.
  Volume labels({21, 21, 21}, 1, ScalarType::UInt8,
                makeWorldFromIndex(glm::dvec3(-20.5), glm::dvec3(2.0), glm::dmat3(1.0)));
  labels.setValue(10, 10, 10, 0, 3);
  labels.setValue(0, 0, 0, 0, 7);
  const LabelPlacement placed = placeLabelVolume(v, labels);
  ASSERT_EQ(placed.labels.size(), 2u);
  EXPECT_FALSE(placed.gridsCoincide);
  EXPECT_EQ(placed.labels[0].number, 3);
  // Nearest neighbour: label index (w + 20.5) / 2, so centres at -1 and 0 mm (9.75, 10.25) map
  // to label voxel 10 and +-1 mm beyond do not: 2^3 voxels.
  EXPECT_EQ(placed.labels[0].voxels.size(), 8u);
  // The corner label: world -20 maps to 0.25 -> 0, -19 to 0.75 -> 1: one voxel.
  EXPECT_EQ(placed.labels[1].voxels.size(), 1u);
}

TEST(RoiStatistics, OverlappingSegmentsKeepTheirOwnMasks) {
  const glm::dvec3 c{0.0, 0.0, 0.0};
  Volume v = cube(1.0, c);
  fillSphere(v, 100.0, 4.0, 4.0);
  v.metadata().frameOfReferenceUid = "1.2.3";
  io::Segmentation seg;
  seg.frameOfReferenceUid = "1.2.3";
  seg.segments = {{1, "a", "", std::nullopt, 1}, {2, "b", "", std::nullopt, 1}};
  // The same grid as the volume, shifted by whole voxels (coincides).
  seg.masks = Volume({5, 5, 1}, 2, ScalarType::UInt8,
                     v.worldFromIndex() * glm::translate(glm::dmat4(1.0), glm::dvec3(18, 18, 20)));
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      seg.masks.setValue(i, j, 0, 0, i < 3);   // 15 voxels
      seg.masks.setValue(i, j, 0, 1, i >= 2);  // 15 voxels, 5 shared
    }
  const LabelPlacement placed = placeSegmentation(v, seg);
  EXPECT_TRUE(placed.gridsCoincide);
  ASSERT_EQ(placed.labels.size(), 2u);
  EXPECT_EQ(placed.labels[0].voxels.size(), 15u);
  EXPECT_EQ(placed.labels[1].voxels.size(), 15u);
  const Volume label = io::labelVolume(seg);
  EXPECT_EQ(label.value(2, 0, 0), 2.0);  // overlap: the higher number
  EXPECT_EQ(label.value(0, 0, 0), 1.0);
  // Another frame of reference is refused.
  seg.frameOfReferenceUid = "9.9";
  EXPECT_THROW(placeSegmentation(v, seg), InputError);
}

}  // namespace
}  // namespace mvw::study
