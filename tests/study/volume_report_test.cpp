// What `mvw info` says about a volume (modules/study VolumeReport), line by line and key by key,
// for a small CT-like volume of known geometry and values.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/study/VolumeReport.h"

namespace mvw::study {
namespace {

namespace fs = std::filesystem;

// 4 x 3 x 2 int16 voxels of 0.5 x 0.75 x 2.5 mm, values -5 .. 18.
Volume ctLike() {
  Volume v({4, 3, 2}, 1, ScalarType::Int16,
           makeWorldFromIndex({-10.25, 3.0, 7.125}, {0.5, 0.75, 2.5}, glm::dmat3(1.0)));
  int n = -5;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) v.setValue(i, j, k, 0, n++);
  auto& md = v.metadata();
  md.sourcePath = "ct.nii";
  md.format = "NIfTI-1";
  md.modality = "CT";
  md.unit = "HU";
  md.notes = {"a note"};
  return v;
}

std::string text(const Volume& v) {
  std::ostringstream out;
  printVolume(out, v);
  return out.str();
}

TEST(VolumeReport, Text) {
  EXPECT_EQ(text(ctLike()),
            "ct.nii\n"
            "  format       NIfTI-1\n"
            "  modality     CT\n"
            "  dimensions   4 x 3 x 2  (int16)\n"
            "  spacing      0.5000 x 0.7500 x 2.5000 mm\n"
            "  origin       -10.250, 3.000, 7.125 mm (LPS)\n"
            "  orientation  LPS\n"
            "  direction    [1.0000 0.0000 0.0000]\n"
            "               [0.0000 1.0000 0.0000]\n"
            "               [0.0000 0.0000 1.0000]\n"
            "  value range  -5 .. 18 HU\n"
            "  note         a note\n");
}

TEST(VolumeReport, DicomSeriesSlicesAndFractionalValues) {
  Volume v({2, 2, 2}, 2, ScalarType::Float32,
           makeWorldFromIndex(glm::dvec3(0.0), glm::dvec3(1.0), glm::dmat3(1.0)));
  v.setValue(0, 0, 0, 0, 0.125);
  for (int c = 0; c < 2; ++c) v.setValue(1, 1, 1, c, 1234.25);
  auto& md = v.metadata();
  md.sourcePath = "dir";
  md.format = "DICOM";
  md.seriesNumber = 7;
  md.seriesDescription = "PET AC";
  md.seriesInstanceUid = "1.2.3";
  md.sliceSpacing = SliceSpacing{2, 3.27, 3.0, 3.5, false, true};
  const std::string t = text(v);
  EXPECT_NE(t.find("  series       #7 \"PET AC\"\n  series UID   1.2.3\n"), std::string::npos) << t;
  EXPECT_NE(t.find("  modality     (not stated)\n"), std::string::npos) << t;
  EXPECT_NE(t.find("  dimensions   2 x 2 x 2 x 2 components  (float32)\n"), std::string::npos) << t;
  EXPECT_NE(t.find("  value range  0 .. 1234\n"), std::string::npos) << t;  // 4 digits
  EXPECT_NE(t.find("  slices       2, spacing 3.270 mm, IRREGULAR (3.000 .. 3.500 mm), resampled "
                   "onto a regular grid\n"),
            std::string::npos)
      << t;
  const nlohmann::json j = volumeJson(v);
  EXPECT_EQ(j["series_number"], 7);
  EXPECT_EQ(j["series_instance_uid"], "1.2.3");
  EXPECT_EQ(j["components"], 2);
  EXPECT_EQ(j["slice_spacing"]["regular"], false);
  EXPECT_DOUBLE_EQ(j["slice_spacing"]["nominal_mm"].get<double>(), 3.27);
}

// One rule for every JSON report (info's, convert's sidecar): null for no number, 0 is one.
TEST(VolumeReport, SeriesNumberJson) {
  EXPECT_TRUE(seriesNumberJson(-1).is_null());
  EXPECT_EQ(seriesNumberJson(0), 0);
  EXPECT_EQ(seriesNumberJson(7), 7);
}

TEST(VolumeReport, Json) {
  const nlohmann::json j = volumeJson(ctLike());
  EXPECT_EQ(j["path"], "ct.nii");
  EXPECT_EQ(j["format"], "NIfTI-1");
  EXPECT_EQ(j["modality"], "CT");
  EXPECT_EQ(j["dimensions"], nlohmann::json({4, 3, 2}));
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["scalar_type"], "int16");
  EXPECT_EQ(j["spacing_mm"], nlohmann::json({0.5, 0.75, 2.5}));
  EXPECT_EQ(j["origin_lps_mm"], nlohmann::json({-10.25, 3.0, 7.125}));
  EXPECT_EQ(j["orientation"], "LPS");
  EXPECT_EQ(j["oblique"], false);
  EXPECT_EQ(j["direction"], nlohmann::json({{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}));
  EXPECT_EQ(j["value_range"], nlohmann::json({-5.0, 18.0}));
  EXPECT_EQ(j["unit"], "HU");
  EXPECT_FALSE(j.contains("series_instance_uid"));  // DICOM only
  EXPECT_FALSE(j.contains("slice_spacing"));
  EXPECT_EQ(j["notes"], nlohmann::json({"a note"}));
}

TEST(VolumeReport, AStudyConfigsVolumesWithTheirRoles) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(ctLike(), dir / "ct.nii");
  io::writeVolume(ctLike(), dir / "pet.nii");
  std::ofstream(dir / "study.json")
      << R"({"anatomical": {"path": "ct.nii"}, "functional": {"path": "pet.nii"}})";
  const auto volumes = readReportedVolumes({dir / "study.json", dir / "ct.nii"}, {}, {});
  ASSERT_EQ(volumes.size(), 3u);
  EXPECT_EQ(volumes[0].role, "anatomical");
  EXPECT_EQ(volumes[1].role.rfind("functional (", 0), 0u) << volumes[1].role;
  EXPECT_EQ(volumes[2].role, "");
  const nlohmann::json j = volumesJson(volumes);
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[0]["role"], "anatomical");
  EXPECT_FALSE(j[2].contains("role"));
  std::ostringstream out;
  printVolumes(out, volumes);
  const std::string t = out.str();
  EXPECT_EQ(t.rfind("[anatomical] ", 0), 0u) << t;
  EXPECT_NE(t.find("\n\n[functional ("), std::string::npos) << t;
  EXPECT_NE(t.find("\n\n" + (dir / "ct.nii").string() + "\n"), std::string::npos) << t;
}

TEST(VolumeReport, ABadInputAnywhereMeansNoReport) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(ctLike(), dir / "ct.nii");
  EXPECT_THROW(readReportedVolumes({dir / "ct.nii", dir / "missing.nii"}, {}, {}), InputError);
}

}  // namespace
}  // namespace mvw::study
