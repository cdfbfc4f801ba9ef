// T1 -> T2 rigid registration on a real MR session (../shared/data/mr-t1-t2-asl: series 5, a
// 1 mm sagittal MPRAGE, and series 6, an oblique axial T2 FSE of 0.43 x 0.43 x 2.5 mm, on one
// frame of reference). The headers agree, so the truth is their identity up to head motion
// between the two series: the T2's header is moved by a known rigid transform and the
// registration must undo it to within 2 degrees and 1.5 mm (at the T1's centre) of the
// header identity. It lands 1.7 degrees and 1.0 mm from it whether it starts there or 7
// degrees and 9 mm away (the head moved between the series, or MI's T1 / T2 peak lies there):
// the two results must also agree with each other, to 0.25 degrees and 0.25 mm.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "SharedData.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

mvw::Volume readSeries(const std::filesystem::path& folder, const char* number) {
  mvw::io::ReadOptions options;
  options.series = std::string(number);
  return mvw::io::readVolume(folder, options);
}

TEST(RealMrRegistration, T1ToT2FromAPerturbedStartRecoversTheHeaderIdentity) {
  MVW_REQUIRE_SHARED_DATA("mr-t1-t2-asl");
  auto series = [&](const char* number) { return readSeries(sharedPath, number); };
  const mvw::Volume t1 = series("5");
  mvw::Volume t2 = series("6");

  // The T2's world moved by `perturbation` (about the T1's centre): a T1 point x now lies at
  // perturbation(x) in the T2's world, so movingFromFixed should come out as perturbation.
  const glm::dvec3 centre = t1.worldFromIndexPoint(glm::dvec3(t1.dimensions() - 1) * 0.5);
  const glm::dmat4 perturbation =
      mvw::resampling::rigidMatrix({glm::dvec3(4, -3, 5) * kDegree, {6, -5, 4}}, centre);
  t2.setWorldFromIndex(perturbation * t2.worldFromIndex());

  // Angle (degrees) and shift at the T1's centre (mm) of a map that should be the identity.
  auto offIdentity = [&](const glm::dmat4& m) {
    const glm::dmat3 rotation(m);
    const double cosine = (rotation[0][0] + rotation[1][1] + rotation[2][2] - 1.0) / 2.0;
    return std::pair{std::acos(std::clamp(cosine, -1.0, 1.0)) / kDegree,
                     glm::length(glm::dvec3(m * glm::dvec4(centre, 1.0)) - centre)};
  };
  const auto r = mvw::resampling::registerRigid(t1, t2);
  const glm::dmat4 found = glm::inverse(perturbation) * r.transform.movingFromFixed();
  const auto [angle, shift] = offIdentity(found);
  std::cout << "T1 -> T2 from 7.1 degrees, 8.8 mm off: " << angle << " degrees, " << shift
            << " mm from the header identity at the T1's centre, " << r.iterations
            << " iterations, " << r.seconds << " s\n";
  RecordProperty("residual_degrees", std::to_string(angle));
  RecordProperty("residual_mm", std::to_string(shift));
  EXPECT_TRUE(r.converged);
  EXPECT_LT(angle, 2.0);
  EXPECT_LT(shift, 1.5);

  t2.setWorldFromIndex(glm::inverse(perturbation) * t2.worldFromIndex());
  const auto fromHeaders = mvw::resampling::registerRigid(t1, t2);
  const auto [angleApart, shiftApart] =
      offIdentity(glm::inverse(fromHeaders.transform.movingFromFixed()) * found);
  std::cout << "    from the header identity: results " << angleApart << " degrees, " << shiftApart
            << " mm apart\n";
  EXPECT_LT(angleApart, 0.25);
  EXPECT_LT(shiftApart, 0.25);
}

// The thin relative-CBF slab (series 18: a Siemens mosaic, 12 slices of 5 mm, 6 mm apart) on
// the whole-head T1: registered directly, it must land where T1 -> T2 followed by T2 -> CBF
// puts it (the T2's slab holds the CBF's). With the sample points over the T1's box (most of
// them off the slab) the direct result was 8.9 degrees and 5.8 mm (mean, within 60 mm of the
// slab's centre) from that chain; with them in the slab, 0.6 degrees and 1.9 mm.
TEST(RealMrRegistration, T1ToCbfSlabAgreesWithT1ToT2ThenT2ToCbf) {
  MVW_REQUIRE_SHARED_DATA("mr-t1-t2-asl");
  auto series = [&](const char* number) { return readSeries(sharedPath, number); };
  const mvw::Volume t1 = series("5"), t2 = series("6"), cbf = series("18");
  const auto direct = mvw::resampling::registerRigid(t1, cbf);
  const auto t1ToT2 = mvw::resampling::registerRigid(t1, t2);
  const auto t2ToCbf = mvw::resampling::registerRigid(t2, cbf);
  EXPECT_TRUE(direct.samplesInMoving);
  EXPECT_FALSE(t2ToCbf.samplesInMoving);
  // cbfFromT1 both ways; their difference over points within 60 mm of the slab's centre.
  const glm::dmat4 chain = t2ToCbf.transform.movingFromFixed() * t1ToT2.transform.movingFromFixed();
  const glm::dmat4 apart = glm::inverse(direct.transform.movingFromFixed()) * chain;
  const glm::dmat3 rotation(apart);
  const double angle =
      std::acos(
          std::clamp((rotation[0][0] + rotation[1][1] + rotation[2][2] - 1.0) / 2.0, -1.0, 1.0)) /
      kDegree;
  const glm::dvec3 centre = direct.transform.centre();
  double meanMm = 0.0;
  int n = 0;
  for (int i = -6; i <= 6; ++i)
    for (int j = -6; j <= 6; ++j)
      for (int k = -6; k <= 6; ++k) {
        const glm::dvec3 offset(10.0 * i, 10.0 * j, 10.0 * k);
        if (glm::length(offset) > 60.0) continue;
        const glm::dvec4 p(centre + offset, 1.0);
        meanMm +=
            glm::length(glm::dvec3(direct.transform.movingFromFixed() * p) - glm::dvec3(chain * p));
        ++n;
      }
  meanMm /= n;
  std::cout << "T1 -> CBF directly against T1 -> T2 -> CBF: " << angle << " degrees, " << meanMm
            << " mm apart (mean within 60 mm of the slab's centre)\n";
  RecordProperty("apart_degrees", std::to_string(angle));
  RecordProperty("apart_mm", std::to_string(meanMm));
  EXPECT_LT(angle, 2.0);
  EXPECT_LT(meanMm, 3.0);
}

}  // namespace
