// Every acquired slice where its header says, on real scanner data (../shared/data): the
// gantry-tilted CT with uneven slice distances, the MR T1 with one missing slice and the
// Siemens ASL mosaics. The reference is independent of mvw and of vtk-dicom: pydicom reads
// each slice and nibabel.nicom unpacks the mosaics (tests/real-data/check-dicom-geometry.py);
// mvw's volume reaches python through mvw's own NIfTI writer.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "SharedData.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"

namespace {

namespace fs = std::filesystem;

fs::path outputDir() {
  const fs::path dir = fs::path(MVW_TEST_OUTPUT_DIR) / "dicom-geometry";
  fs::create_directories(dir);
  return dir;
}

// Writes `volume` as NIfTI, runs the python check and returns its JSON summary.
nlohmann::json check(const mvw::Volume& volume, const std::string& name, const std::string& mode,
                     const std::string& args) {
  const fs::path dir = outputDir();
  const fs::path nifti = dir / (name + ".nii.gz"), json = dir / (name + ".json");
  const fs::path log = dir / (name + ".log");
  fs::remove(json);
  mvw::io::writeVolume(volume, nifti);
  const std::string script =
      std::string(MVW_SOURCE_DIR) + "/tests/real-data/check-dicom-geometry.py";
  const std::string command = "/usr/bin/python3 '" + script + "' " + mode + " '" + nifti.string() +
                              "' '" + json.string() + "' " + args + " > '" + log.string() +
                              "' 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command << "\nsee " << log;
  std::ifstream in(json);
  if (!in) return {};
  std::ifstream text(log);
  std::cout << name << ": " << std::string(std::istreambuf_iterator<char>(text), {});
  return nlohmann::json::parse(in);
}

bool hasNote(const mvw::Volume& v, const std::string& part) {
  const auto& notes = v.metadata().notes;
  return std::any_of(notes.begin(), notes.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

std::string shellQuoted(const fs::path& p) { return " '" + p.string() + "'"; }

TEST(RealDicomGeometry, TiltedCtWithUnevenSlicesLandsWhereTheHeadersSay) {
  MVW_REQUIRE_SHARED_DATA("ct-head-gantry-tilt");
  const mvw::Volume ct = mvw::io::readVolume(sharedPath);
  ASSERT_TRUE(ct.metadata().sliceSpacing.has_value());
  const auto& ss = *ct.metadata().sliceSpacing;
  EXPECT_EQ(ss.slices, 28);
  EXPECT_FALSE(ss.regular);
  EXPECT_TRUE(ss.resampled);
  EXPECT_NEAR(ss.minimum, 1.081, 0.002);  // 1.14 mm in S at 18.5 degrees
  EXPECT_NEAR(ss.maximum, 6.999, 0.002);
  EXPECT_TRUE(hasNote(ct, "gantry tilt 18.5 degrees")) << ct.metadata().notes.front();
  EXPECT_TRUE(hasNote(ct, "4.002 mm x 13 (slices 1-14), 1.081 mm (slices 14-15), 6.999 mm x 13"));
  // An orthogonal grid: the columns of the direction matrix are orthonormal.
  const glm::dmat3 d = ct.direction();
  EXPECT_NEAR(glm::dot(d[0], d[2]), 0.0, 1e-9);
  EXPECT_NEAR(glm::dot(d[1], d[2]), 0.0, 1e-9);
  // The smallest distance, adjusted so the first and last slices lie on grid planes.
  EXPECT_NEAR(ct.spacing().z, 1.0834, 2e-4);  // 144.09 mm / 133
  EXPECT_EQ(ct.dimensions().z, 134);
  EXPECT_EQ(ct.dimensions().x, 512);
  EXPECT_GT(ct.dimensions().y, 512 + 90);  // grown to cover the slices' 48 mm shift
  const auto result = check(ct, "ct-gantry-tilt", "slices", shellQuoted(sharedPath) + " all");
  ASSERT_FALSE(result.empty());
  EXPECT_EQ(result["slices"], 28);
  EXPECT_EQ(result["outside"], 0);
  // Within interpolation error (measured 0.0187 and 0.0086; 0.189 and 0.137 with one spacing):
  // the acquired positions fall between grid planes, and in-plane the tilt shift is sampled
  // bilinearly twice (by mvw, then by the check).
  EXPECT_LT(result["max_ratio"].get<double>(), 0.025);
  EXPECT_LT(result["mean_ratio"].get<double>(), 0.012);
}

TEST(RealDicomGeometry, T1WithAMissingSliceKeepsEveryAcquiredSliceExactly) {
  MVW_REQUIRE_SHARED_DATA("mr-t1-t2-asl");
  mvw::io::ReadOptions options;
  options.series = "5";
  const mvw::Volume t1 = mvw::io::readVolume(sharedPath, options);
  ASSERT_TRUE(t1.metadata().sliceSpacing.has_value());
  EXPECT_EQ(t1.metadata().sliceSpacing->slices, 175);
  EXPECT_TRUE(t1.metadata().sliceSpacing->resampled);
  EXPECT_EQ(t1.dimensions(), glm::ivec3(192, 192, 176));
  EXPECT_NEAR(t1.spacing().z, 1.0, 1e-6);
  EXPECT_TRUE(hasNote(t1, "gap of 2.000 mm after slice 114 of 175"));
  EXPECT_FALSE(hasNote(t1, "gantry tilt"));
  const auto result = check(t1, "mr-t1", "slices", shellQuoted(sharedPath) + " 5");
  ASSERT_FALSE(result.empty());
  EXPECT_EQ(result["slices"], 175);
  EXPECT_EQ(result["outside"], 0);
  EXPECT_LE(result["max_abs_diff"].get<double>(), 1e-3);  // on grid points: exact
}

TEST(RealDicomGeometry, ObliqueT2WithAMissingSliceKeepsEveryAcquiredSliceExactly) {
  MVW_REQUIRE_SHARED_DATA("mr-t1-t2-asl");
  mvw::io::ReadOptions options;
  options.series = "6";
  const mvw::Volume t2 = mvw::io::readVolume(sharedPath, options);
  EXPECT_EQ(t2.dimensions(), glm::ivec3(384, 512, 56));
  EXPECT_NEAR(t2.spacing().z, 2.5, 1e-6);
  EXPECT_TRUE(hasNote(t2, "gap of 5.000 mm after slice 34 of 55"));
  const auto result = check(t2, "mr-t2", "slices", shellQuoted(sharedPath) + " 6");
  ASSERT_FALSE(result.empty());
  EXPECT_EQ(result["slices"], 55);
  EXPECT_EQ(result["outside"], 0);
  EXPECT_LE(result["max_abs_diff"].get<double>(), 1e-3);
}

class RealMosaic : public ::testing::TestWithParam<const char*> {};

TEST_P(RealMosaic, UnpacksLikeNibabelOnTheT1FrameOfReference) {
  MVW_REQUIRE_SHARED_DATA("mr-t1-t2-asl");
  mvw::io::ReadOptions options;
  options.series = GetParam();
  const mvw::Volume asl = mvw::io::readVolume(sharedPath, options);
  EXPECT_EQ(asl.dimensions(), glm::ivec3(64, 64, 12));
  EXPECT_NEAR(asl.spacing().x, 3.4375, 1e-6);
  EXPECT_NEAR(asl.spacing().z, 6.0, 1e-4);
  EXPECT_TRUE(hasNote(asl, "Siemens MOSAIC unpacked: 12 tiles of 64 x 64"));
  std::string file;
  for (const auto& e : fs::directory_iterator(sharedPath))
    if (e.path().filename() == (std::string(GetParam()) == "17" ? "36747043" : "36747062"))
      file = e.path().string();
  ASSERT_FALSE(file.empty());
  const auto result =
      check(asl, std::string("asl-series-") + GetParam(), "mosaic", shellQuoted(fs::path(file)));
  ASSERT_FALSE(result.empty());
  EXPECT_EQ(result["outside"], 0);
  EXPECT_LT(result["max_position_error_mm"].get<double>(), 0.01);
  EXPECT_LE(result["max_abs_diff"].get<double>(), 1e-6 * result["reference_max"].get<double>());
  // On the T1's frame of reference: the perfusion volume's centre lies inside the T1 volume.
  options.series = "5";
  const mvw::Volume t1 = mvw::io::readVolume(sharedPath, options);
  const glm::dvec3 centre = asl.worldFromIndexPoint(glm::dvec3(asl.dimensions() - 1) * 0.5);
  const glm::dvec3 inT1 = glm::inverse(t1.worldFromIndex()) * glm::dvec4(centre, 1.0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_GT(inT1[a], 0.0) << a;
    EXPECT_LT(inT1[a], t1.dimensions()[a] - 1.0) << a;
  }
}

INSTANTIATE_TEST_SUITE_P(Series, RealMosaic, ::testing::Values("17", "18"));

}  // namespace
