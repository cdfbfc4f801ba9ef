// `mvw bench register`'s pieces that need neither elastix nor a CT (validate::RegistrationBench):
// reading elastix's Euler transform, the error split on known matrices, the seeded cases, the
// per-voxel summary and its table.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/resampling/Transform.h"
#include "mvw/validate/RegistrationBench.h"

namespace mvw::validate {
namespace {

namespace fs = std::filesystem;

constexpr double kDegree = std::numbers::pi / 180.0;

// A TransformParameters.0.txt as elastix 5 writes it for a rigid run (the lines it reads and
// some it does not).
std::string elastixFile(const std::string& extra = "",
                        const std::string& parameters = "0.1 -0.2 0.3 1.5 -2 3.25",
                        const std::string& initial = "NoInitialTransform") {
  return "(Transform \"EulerTransform\")\n(NumberOfParameters 6)\n(TransformParameters " +
         parameters + ")\n(InitialTransformParametersFileName \"" + initial +
         "\")\n(HowToCombineTransforms \"Compose\")\n(FixedImageDimension 3)\n"
         "(CenterOfRotationPoint 10.0 -20.0 30.5)\n" +
         extra;
}

void expectNear(const glm::dmat4& a, const glm::dmat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(a[c][r], b[c][r], 1e-12) << "[" << c << "][" << r << "]";
}

TEST(RegistrationBench, ElastixEulerIsRigidMatrixOfItsParametersAboutItsCentre) {
  const glm::dmat4 m = elastixEuler(elastixFile(), "TransformParameters.0.txt");
  expectNear(m,
             resampling::rigidMatrix({{0.1, -0.2, 0.3}, {1.5, -2.0, 3.25}}, {10.0, -20.0, 30.5}));
  // The centre maps to itself plus the translation.
  const glm::dvec4 c = m * glm::dvec4(10.0, -20.0, 30.5, 1.0);
  EXPECT_NEAR(c.x, 11.5, 1e-12);
  EXPECT_NEAR(c.y, -22.0, 1e-12);
  EXPECT_NEAR(c.z, 33.75, 1e-12);
}

TEST(RegistrationBench, ComputeZyxRotatesInTheOtherOrder) {
  const glm::dmat4 m = elastixEuler(elastixFile("(ComputeZYX \"true\")\n"), "t.txt");
  const glm::dmat3 rx = resampling::eulerRotation({0.1, 0, 0}),
                   ry = resampling::eulerRotation({0, -0.2, 0}),
                   rz = resampling::eulerRotation({0, 0, 0.3});
  const glm::dmat3 r = rz * ry * rx;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m[c][k], r[c][k], 1e-12);
  const glm::dvec3 centre(10.0, -20.0, 30.5);
  const glm::dvec3 t = centre - r * centre + glm::dvec3(1.5, -2.0, 3.25);
  EXPECT_NEAR(m[3].x, t.x, 1e-12);
  EXPECT_NEAR(m[3].y, t.y, 1e-12);
  EXPECT_NEAR(m[3].z, t.z, 1e-12);
  // Not the default order's matrix: the two conventions differ for rotations about two axes.
  const glm::dmat4 zxy = elastixEuler(elastixFile(), "t.txt");
  EXPECT_GT(std::abs(zxy[0][1] - m[0][1]) + std::abs(zxy[2][0] - m[2][0]), 1e-3);
}

// Each refusal names the file and what is wrong with it.
void expectRefused(const std::string& text, const std::string& problem) {
  try {
    elastixEuler(text, "dir/TransformParameters.0.txt");
    ADD_FAILURE() << "no error for: " << problem;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), fs::path("dir/TransformParameters.0.txt"));
    EXPECT_EQ(e.problem(), problem);
  }
}

TEST(RegistrationBench, AnythingButAPlainEulerTransformIsRefused) {
  expectRefused("(Transform \"AffineTransform\")\n(TransformParameters 1 0 0 0 1 0 0 0 1 0 0 0)",
                "is not an EulerTransform");
  expectRefused(elastixFile("", "0.1 -0.2 0.3 1.5 -2 3.25", "previous.txt"),
                "chains an initial transform: not supported here");
  expectRefused(elastixFile("", "0.1 -0.2 0.3 1.5 -2"), "expected 6 parameters and a 3-D centre");
  expectRefused(
      "(Transform \"EulerTransform\")\n(InitialTransformParametersFileName "
      "\"NoInitialTransform\")\n"
      "(CenterOfRotationPoint 0 0 0)\n",
      "has no TransformParameters");
}

TEST(RegistrationBench, AMissingTransformFilePointsAtElastixLog) {
  const fs::path dir = test::scratchDir();
  try {
    readElastixEuler(dir / "TransformParameters.0.txt");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "elastix wrote no transform (see elastix.log next to it)");
  }
  std::ofstream(dir / "TransformParameters.0.txt") << elastixFile();
  expectNear(readElastixEuler(dir / "TransformParameters.0.txt"),
             elastixEuler(elastixFile(), "t.txt"));
}

TEST(RegistrationBench, TheErrorSplitsIntoTheCentresShiftAndTheResidualRotation) {
  const glm::dvec3 centre(5.0, -3.0, 12.0);
  const glm::dmat4 truth = resampling::rigidMatrix({{0.05, 0.1, -0.2}, {4.0, 1.0, -2.0}}, centre);
  // The same rotation, shifted: all of the error is the centre's.
  glm::dmat4 shifted = truth;
  shifted[3] += glm::dvec4(0.5, -1.0, 2.0, 0.0);
  ErrorSplit e = splitError(shifted, truth, centre);
  EXPECT_NEAR(e.centreMm.x, 0.5, 1e-12);
  EXPECT_NEAR(e.centreMm.y, -1.0, 1e-12);
  EXPECT_NEAR(e.centreMm.z, 2.0, 1e-12);
  EXPECT_NEAR(glm::length(e.rotationDeg), 0.0, 1e-9);
  // One degree more about S (z), about the centre: the centre stays, the rotation is +1 degree
  // about z (to first order: sin 1 degree).
  const double a = 1.0 * kDegree;
  glm::dmat4 rz(1.0);
  rz[0][0] = std::cos(a);
  rz[0][1] = std::sin(a);
  rz[1][0] = -std::sin(a);
  rz[1][1] = std::cos(a);
  glm::dmat4 toCentre(1.0), back(1.0);
  toCentre[3] = glm::dvec4(-centre, 1.0);
  back[3] = glm::dvec4(centre, 1.0);
  const glm::dvec3 image = glm::dvec3(truth * glm::dvec4(centre, 1.0));
  glm::dmat4 aboutImage(1.0), fromImage(1.0);
  aboutImage[3] = glm::dvec4(-image, 1.0);
  fromImage[3] = glm::dvec4(image, 1.0);
  e = splitError(fromImage * rz * aboutImage * truth, truth, centre);
  EXPECT_NEAR(glm::length(e.centreMm), 0.0, 1e-9);
  EXPECT_NEAR(e.rotationDeg.x, 0.0, 1e-9);
  EXPECT_NEAR(e.rotationDeg.y, 0.0, 1e-9);
  EXPECT_NEAR(e.rotationDeg.z, std::sin(a) / kDegree, 1e-9);
  EXPECT_EQ(describe({{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}),
            "centre (+0.00, +0.00, +0.00) mm, rotation (+0.00, +0.00, +1.00) deg");
  EXPECT_EQ(describe({{-0.125, 2.0, 10.5}, {0.0, -0.3, 1.0}}),
            "centre (-0.12, +2.00, +10.50) mm, rotation (+0.00, -0.30, +1.00) deg");
}

TEST(RegistrationBench, CasesAreSeededPerVoxelSizeAndInRange) {
  RegistrationBenchOptions o;
  o.cases = 6;
  o.maxDegrees = 3.0;
  o.maxMm = 7.0;
  const auto a = randomBenchCases(o, 1), b = randomBenchCases(o, 1), c = randomBenchCases(o, 2);
  ASSERT_EQ(a.size(), 6u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].degrees, b[i].degrees);
    EXPECT_EQ(a[i].mm, b[i].mm);
    EXPECT_NE(a[i].degrees, c[i].degrees);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(a[i].degrees[k]), 3.0);
      EXPECT_LE(std::abs(a[i].mm[k]), 7.0);
    }
  }
}

// The four 5 mm transforms of seed 1, as known_transform_test lists them (rounded to 0.1).
TEST(RegistrationBench, TheDefaultFiveMillimetreCasesAreTheOnesTheUnitTestsReuse) {
  const RegistrationBenchOptions o;
  ASSERT_EQ(o.voxelMm[2], 5.0);
  const auto cases = randomBenchCases(o, 2);
  const std::vector<std::pair<glm::dvec3, glm::dvec3>> known = {
      {{-4.0, -2.4, 5.4}, {7.9, -2.8, -7.9}},
      {{-0.4, -6.2, -4.7}, {-4.0, -10.0, 8.9}},
      {{-6.0, -0.2, 6.0}, {-2.4, 3.8, -7.0}},
      {{-4.0, 6.1, 1.5}, {5.8, -3.6, -1.0}}};
  ASSERT_EQ(cases.size(), known.size());
  for (std::size_t i = 0; i < known.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(cases[i].degrees[k], known[i].first[k], 0.05) << i;
      EXPECT_NEAR(cases[i].mm[k], known[i].second[k], 0.05) << i;
    }
}

BenchRow row(double before, double ours, double elastix, double oursS, double elastixS) {
  BenchRow r;
  r.before = before;
  r.oursTre = ours;
  r.elastixTre = elastix;
  r.oursSeconds = oursS;
  r.elastixSeconds = elastixS;
  r.oursError = {{ours, 0, 0}, {0, 0, 0.5}};
  r.elastixError = {{0, elastix, 0}, {0.25, 0, 0}};
  return r;
}

TEST(RegistrationBench, TheSummaryAveragesTheCasesAndCountsMvwsWins) {
  const BenchSummary s = summarise(4.0, {row(9, 0.2, 0.4, 1.0, 3.0), row(8, 0.6, 0.5, 2.0, 5.0)});
  EXPECT_EQ(s.voxelMm, 4.0);
  EXPECT_EQ(s.pairs, 2);
  EXPECT_EQ(s.better, 1);
  EXPECT_NEAR(s.oursMean, 0.4, 1e-12);
  EXPECT_NEAR(s.oursMax, 0.6, 1e-12);
  EXPECT_NEAR(s.elMean, 0.45, 1e-12);
  EXPECT_NEAR(s.elMax, 0.5, 1e-12);
  EXPECT_NEAR(s.oursTime, 3.0, 1e-12);
  EXPECT_NEAR(s.elTime, 8.0, 1e-12);
  EXPECT_NEAR(s.oursBias.centreMm.x, 0.4, 1e-12);
  EXPECT_NEAR(s.oursBias.rotationDeg.z, 0.5, 1e-12);
  EXPECT_NEAR(s.elastixBias.centreMm.y, 0.45, 1e-12);
  EXPECT_NEAR(s.elastixBias.rotationDeg.x, 0.25, 1e-12);
}

TEST(RegistrationBench, TheTablesSayEachVoxelSizeAndTheVerdict) {
  RegistrationBenchOptions o;
  o.cases = 2;
  const BenchSummary pass =
      summarise(4.0, {row(9, 0.2, 0.4, 1.0, 3.0), row(8, 0.6, 0.5, 2.0, 5.0)});
  const BenchSummary fail =
      summarise(6.0, {row(9, 0.9, 0.4, 1.0, 2.0), row(8, 0.7, 0.5, 1.0, 2.0)});
  std::ostringstream out;
  EXPECT_TRUE(printBenchSummary(o, {pass}, out));
  EXPECT_EQ(out.str(),
            "\nTRE over 2 random transforms per voxel size (noise 0.1):\n"
            "voxel mm mvw mean / max mm      elastix mean / max mm  mvw <= el.   mvw s     "
            "elastix s   elastix/mvw time\n"
            "4        0.400 / 0.600          0.450 / 0.500          1/2          3.00      8.00 "
            "       2.67x\n"
            "\nMean error over the cases (a bias; single cases scatter about it):\n"
            "4        mvw     centre (+0.40, +0.00, +0.00) mm, rotation (+0.00, +0.00, +0.50) deg\n"
            "         elastix centre (+0.00, +0.45, +0.00) mm, rotation (+0.25, +0.00, +0.00) deg\n"
            "verdict: mvw's mean TRE is at or below elastix's at every voxel size\n");
  std::ostringstream failed;
  EXPECT_FALSE(printBenchSummary(o, {pass, fail}, failed));
  EXPECT_NE(failed.str().find("6        0.800 / 0.900          0.450 / 0.500          0/2"
                              "          2.00      4.00        2.00x  <- mvw's mean TRE is above "
                              "elastix's\n"),
            std::string::npos)
      << failed.str();
  EXPECT_NE(
      failed.str().find("verdict: FAIL: mvw's mean TRE is above elastix's at some voxel size\n"),
      std::string::npos);
}

TEST(RegistrationBench, AMissingElastixOrParameterFileIsBadInput) {
  const fs::path dir = test::scratchDir();
  RegistrationBenchOptions o;
  o.elastix = (dir / "no-elastix").string();
  o.parameters = (dir / "rigid.txt").string();
  std::ostringstream out;
  EXPECT_THROW(runRegistrationBench(o, out), InputError);
  o.elastix = "/bin/sh";
  try {
    runRegistrationBench(o, out);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "no such parameter file");
  }
  EXPECT_EQ(out.str(), "");
}

}  // namespace
}  // namespace mvw::validate
