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

TEST(RealMrRegistration, T1ToT2FromAPerturbedStartRecoversTheHeaderIdentity) {
  MVW_REQUIRE_SHARED_DATA("mr-t1-t2-asl");
  auto series = [&](const char* number) {
    mvw::io::ReadOptions options;
    options.series = std::string(number);
    return mvw::io::readVolume(sharedPath, options);
  };
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

}  // namespace
