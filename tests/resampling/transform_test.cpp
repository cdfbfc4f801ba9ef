// Transform (issue 3): the ITK transform file (written, read back, its conventions, bad files
// refused naming the file) and the rigid parameters; registration and `mvw register` write and
// read transforms through it, so every matrix is checked against hand-computed values.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {
namespace {

namespace fs = std::filesystem;

double maxAbsDifference(const glm::dmat4& a, const glm::dmat4& b) {
  double d = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
  return d;
}

glm::dmat4 someAffine() {
  glm::dmat4 m = rigidMatrix({{0.3, -0.2, 0.7}, {12.5, -3.25, 40.0}}, {1.0, 2.0, 3.0});
  m[0][1] += 0.05;  // shear and scale: the file must carry a general affine too
  m[2][2] *= 1.1;
  return m;
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(Transform, ItkFileRoundTripKeepsTheMatrix) {
  const fs::path file = test::scratchDir() / "affine.tfm";
  const Transform t(someAffine(), {-4.0, 7.5, 100.25});
  t.writeItk(file);
  const Transform r = Transform::readItk(file);
  EXPECT_LT(maxAbsDifference(r.fixedFromMoving(), t.fixedFromMoving()), 1e-9);
  EXPECT_LT(maxAbsDifference(r.movingFromFixed(), t.movingFromFixed()), 1e-9);
  EXPECT_LT(glm::length(r.centre() - t.centre()), 1e-12);
  EXPECT_FALSE(fs::exists(fs::path(file) += ".tmp"));
}

TEST(Transform, ItkFileHoldsMovingFromFixedWithTranslationAboutTheCentre) {
  // The functional volume's content sits 10 mm further left (+x in LPS) than the anatomy's:
  // anatomicalFromFunctional shifts by -10, and ITK's file (fixed -> moving) by +10.
  const glm::dmat4 fixedFromMoving = glm::translate(glm::dmat4(1.0), glm::dvec3(-10.0, 0.0, 0.0));
  const fs::path file = test::scratchDir() / "shift.tfm";
  Transform(fixedFromMoving, {5.0, 6.0, 7.0}).writeItk(file);
  std::ifstream in(file);
  std::string header, index, type, parameters, fixed;
  std::getline(in, header);
  std::getline(in, index);
  std::getline(in, type);
  std::getline(in, parameters);
  std::getline(in, fixed);
  EXPECT_EQ(header, "#Insight Transform File V1.0");
  EXPECT_EQ(type, "Transform: AffineTransform_double_3_3");
  EXPECT_EQ(parameters, "Parameters: 1 0 0 0 1 0 0 0 1 10 0 0");
  EXPECT_EQ(fixed, "FixedParameters: 5 6 7");

  // An ITK Euler3D file: 90 degrees about z around (10, 0, 0) plus (0, 0, 2) maps the fixed
  // point (11, 0, 0) to the moving point (10, 1, 2).
  const fs::path euler = test::scratchDir() / "euler.tfm";
  writeText(euler,
            "#Insight Transform File V1.0\n#Transform 0\nTransform: Euler3DTransform_double_3_3\n"
            "Parameters: 0 0 1.5707963267948966 0 0 2\nFixedParameters: 10 0 0 0\n");
  const Transform e = Transform::readItk(euler);
  EXPECT_LT(glm::length(e.movingFromFixedPoint({11, 0, 0}) - glm::dvec3(10, 1, 2)), 1e-12);
  EXPECT_LT(glm::length(e.fixedFromMovingPoint({10, 1, 2}) - glm::dvec3(11, 0, 0)), 1e-12);
  EXPECT_TRUE(e.isRigid());
}

TEST(Transform, BadFilesThrowInputErrorNamingTheFile) {
  const fs::path dir = test::scratchDir();
  const std::string head = "#Insight Transform File V1.0\n#Transform 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"empty.tfm", ""},
      {"noheader.tfm",
       "Transform: AffineTransform_double_3_3\nParameters: 1 0 0 0 1 0 0 0 1 0 0 "
       "0\nFixedParameters: 0 0 0\n"},
      {"short.tfm", head + "Transform: AffineTransform_double_3_3\nParameters: 1 0 0 0 1 0 0 0 1 0 "
                           "0\nFixedParameters: 0 0 0\n"},
      {"text.tfm", head + "Transform: AffineTransform_double_3_3\nParameters: 1 0 0 0 one 0 0 0 1 "
                          "0 0 0\nFixedParameters: 0 0 0\n"},
      {"nan.tfm", head + "Transform: AffineTransform_double_3_3\nParameters: 1 0 0 0 nan 0 0 0 1 0 "
                         "0 0\nFixedParameters: 0 0 0\n"},
      {"singular.tfm", head + "Transform: AffineTransform_double_3_3\nParameters: 1 0 0 2 0 0 0 0 "
                              "1 0 0 0\nFixedParameters: 0 0 0\n"},
      {"bspline.tfm",
       head +
           "Transform: BSplineTransform_double_3_3\nParameters: 0 0 0\nFixedParameters: 0 0 0\n"},
      {"two.tfm",
       head + "Transform: TranslationTransform_double_3_3\nParameters: 1 2 3\nFixedParameters:\n"
              "#Transform 1\nTransform: TranslationTransform_double_3_3\nParameters: 1 2 "
              "3\nFixedParameters:\n"},
      {"nofixed.tfm",
       head + "Transform: AffineTransform_double_3_3\nParameters: 1 0 0 0 1 0 0 0 1 0 0 0\n"},
  };
  for (const auto& [name, text] : cases) {
    writeText(dir / name, text);
    try {
      Transform::readItk(dir / name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), dir / name) << e.what();
    }
  }
  EXPECT_THROW(Transform::readItk(dir / "missing.tfm"), InputError);
  // The same content with a good matrix is read, so the cases above fail for their reason.
  writeText(
      dir / "good.tfm",
      head + "Transform: TranslationTransform_double_3_3\nParameters: 1 2 3\nFixedParameters:\n");
  EXPECT_LT(glm::length(Transform::readItk(dir / "good.tfm").movingFromFixedPoint({0, 0, 0}) -
                        glm::dvec3(1, 2, 3)),
            1e-12);
}

TEST(Transform, RigidParametersRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-1.4, 1.4), shift(-50.0, 50.0);
  for (int n = 0; n < 200; ++n) {
    const RigidParameters p{{angle(rng), angle(rng), angle(rng)},
                            {shift(rng), shift(rng), shift(rng)}};
    const glm::dvec3 centre(shift(rng), shift(rng), shift(rng));
    const glm::dmat4 m = rigidMatrix(p, centre);
    EXPECT_TRUE(Transform(m).isRigid());
    const RigidParameters q = rigidParameters(m, centre);
    EXPECT_LT(glm::length(q.angles - p.angles), 1e-9);
    EXPECT_LT(glm::length(q.translation - p.translation), 1e-9);
    EXPECT_LT(maxAbsDifference(rigidMatrix(q, centre), m), 1e-9);
  }
  // The centre is a fixed point of the rotation part: R (c - c) + c + t = c + t.
  const glm::dvec3 c(10, -20, 30);
  const glm::dmat4 m = rigidMatrix({{0.2, 0.3, -0.4}, {1, 2, 3}}, c);
  EXPECT_LT(glm::length(glm::dvec3(m * glm::dvec4(c, 1.0)) - (c + glm::dvec3(1, 2, 3))), 1e-12);
  EXPECT_FALSE(Transform(someAffine()).isRigid());
}

}  // namespace
}  // namespace mvw::resampling
