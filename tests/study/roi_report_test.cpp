// The report `mvw stats` prints (modules/study RoiReport) on a 4 x 4 x 4 volume of 2 mm voxels
// whose value is its own linear index (i + 4 j + 16 k), so every figure is worked by hand: a
// voxel is 0.008 ml; the box (0,0,0)..(2,2,0) mm holds the values 0, 1, 4, 5 (mean 2.5, SD
// sqrt(17 / 4) = 2.062); at or above 4 they leave 4 and 5 (0.016 ml, mean 4.5, TLG 0.072).
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/dicomout/SegmentationWriter.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/study/RoiReport.h"

namespace mvw::study {
namespace {

namespace fs = std::filesystem;

Volume indexVolume() {
  Volume v({4, 4, 4}, 1, ScalarType::Float32,
           makeWorldFromIndex(glm::dvec3(0.0), glm::dvec3(2.0), glm::dmat3(1.0)));
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) v.setValue(i, j, k, 0, i + 4 * j + 16 * k);
  v.metadata().unit = "Bq/ml";
  v.metadata().sourcePath = "tiny.nii";
  return v;
}

RoiRequest boxRequest() {
  RoiRequest r;
  r.box = BoxRoi{{0, 0, 0}, {2, 2, 0}};
  return r;
}

const auto kNoNote = [](const std::string& note) { ADD_FAILURE() << "unexpected note: " << note; };

std::string text(const Volume& v, const RoiReport& report) {
  std::ostringstream out;
  printRoiReport(out, v, report);
  return out.str();
}

TEST(RoiReport, RequestOfTheCommandLinesOptions) {
  RoiOptions o;
  o.sphere = {1.0, 2.0, 3.0, 4.5};
  RoiRequest r = roiRequestOf(o);
  ASSERT_TRUE(r.sphere);
  EXPECT_EQ(r.sphere->centre, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(r.sphere->radiusMm, 4.5);
  EXPECT_FALSE(r.box);
  EXPECT_EQ(r.threshold.kind, Threshold::Kind::None);

  o = {};
  o.box = {-1.0, -2.0, -3.0, 1.0, 2.0, 3.0};
  o.thresholdFraction = 0.41;
  r = roiRequestOf(o);
  ASSERT_TRUE(r.box);
  EXPECT_EQ(r.box->min, glm::dvec3(-1.0, -2.0, -3.0));
  EXPECT_EQ(r.box->max, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(r.threshold.kind, Threshold::Kind::FractionOfMax);
  EXPECT_EQ(r.threshold.value, 0.41);

  o = {};
  o.labels = "seg.dcm";
  o.label = 3;
  o.threshold = 2.5;
  r = roiRequestOf(o);
  EXPECT_FALSE(r.sphere);
  EXPECT_FALSE(r.box);
  EXPECT_EQ(r.labels, fs::path("seg.dcm"));
  EXPECT_EQ(r.label, 3);
  EXPECT_EQ(r.threshold.kind, Threshold::Kind::Absolute);
  EXPECT_EQ(r.threshold.value, 2.5);
}

TEST(RoiReport, OptionsProblemsAreSaidInTheCallersNames) {
  RoiOptions o;
  EXPECT_FALSE(roiOptionsProblem(o));  // none: a folder's SEG may give the labels later
  o.sphere = {0, 0, 0, 5};
  o.thresholdFraction = 1.0;
  EXPECT_FALSE(roiOptionsProblem(o));
  o.box = {0, 0, 0, 1, 1, 1};
  auto p = roiOptionsProblem(o);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->option, "ROI");
  EXPECT_EQ(p->problem,
            "give exactly one of --sphere X Y Z R, --box X0 Y0 Z0 X1 Y1 Z1 or --labels FILE");
  o.box.clear();
  o.threshold = 2.5;
  const RoiOptionNames python{"sphere", "box", "labels", "threshold", "threshold_fraction"};
  p = roiOptionsProblem(o, python);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->problem, "give threshold or threshold_fraction, not both");
  o.threshold = std::numeric_limits<double>::quiet_NaN();
  for (double bad : {0.0, -0.1, 1.01, 2.0}) {
    o.thresholdFraction = bad;
    p = roiOptionsProblem(o);
    ASSERT_TRUE(p) << bad;
    EXPECT_EQ(p->option, "--threshold-fraction");
    EXPECT_EQ(p->problem, "must lie in (0, 1], e.g. 0.41");
  }
  // A label is of labels: given with a sphere or a box, a problem; with no ROI at all, the
  // default label map's (defaultLabels), so none yet.
  o.thresholdFraction = std::numeric_limits<double>::quiet_NaN();
  o.label = 2;
  p = roiOptionsProblem(o);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->option, "--label");
  EXPECT_EQ(p->problem, "needs --labels FILE");
  o.sphere.clear();
  EXPECT_FALSE(roiOptionsProblem(o));
  o.labels = "seg.dcm";
  EXPECT_FALSE(roiOptionsProblem(o));
}

TEST(RoiReport, BoxWithAThresholdAsText) {
  const Volume v = indexVolume();
  RoiRequest request = boxRequest();
  request.threshold = {Threshold::Kind::Absolute, 4.0};
  const RoiReport report = roiReport(v, request, "tiny.nii", kNoNote);
  EXPECT_FALSE(report.total);
  EXPECT_EQ(text(v, report),
            "tiny.nii  (modality not stated, values in Bq/ml)\n"
            "box 0.0, 0.0, 0.0 .. 2.0, 2.0, 0.0 mm LPS\n"
            "  voxels       4  (0.032 ml)\n"
            "  max          5 Bq/ml  at 2.0, 2.0, 0.0 mm LPS\n"
            "  mean         2.5 Bq/ml\n"
            "  sd           2.062 Bq/ml\n"
            "  metabolic    0.016 ml  (2 voxels >= 4 Bq/ml)\n"
            "  metab. mean  4.5 Bq/ml  (mean of the metabolic volume)\n"
            "  TLG          0.072 Bq/ml x ml  (metabolic volume x its mean)\n");
}

TEST(RoiReport, BoxAsJson) {
  const Volume v = indexVolume();
  RoiRequest request = boxRequest();
  request.threshold = {Threshold::Kind::FractionOfMax, 0.5};  // 2.5: the values 4 and 5
  const nlohmann::json j = roiReportJson(roiReport(v, request, "tiny.nii", kNoNote));
  ASSERT_EQ(j.size(), 1u);
  const nlohmann::json& roi = j[0];
  EXPECT_EQ(roi["roi"], "box 0.0, 0.0, 0.0 .. 2.0, 2.0, 0.0 mm LPS");
  EXPECT_FALSE(roi.contains("label"));
  EXPECT_EQ(roi["voxels"], 4);
  EXPECT_EQ(roi["voxels_no_data"], 0);
  EXPECT_DOUBLE_EQ(roi["volume_ml"].get<double>(), 0.032);
  EXPECT_EQ(roi["unit"], "Bq/ml");
  EXPECT_EQ(roi["max"], 5.0);
  EXPECT_EQ(roi["max_at_lps_mm"], nlohmann::json({2.0, 2.0, 0.0}));
  EXPECT_DOUBLE_EQ(roi["mean"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(roi["sd"].get<double>(), std::sqrt(17.0 / 4.0));
  EXPECT_FALSE(roi.contains("peak"));  // not an SUV
  EXPECT_DOUBLE_EQ(roi["threshold"].get<double>(), 2.5);
  EXPECT_EQ(roi["metabolic_voxels"], 2);
  EXPECT_DOUBLE_EQ(roi["metabolic_volume_ml"].get<double>(), 0.016);
  EXPECT_DOUBLE_EQ(roi["metabolic_mean"].get<double>(), 4.5);
  EXPECT_NEAR(roi["tlg"].get<double>(), 0.072, 1e-15);
}

TEST(RoiReport, FractionOfMaxSaysThePercentage) {
  const Volume v = indexVolume();
  RoiRequest request = boxRequest();
  request.threshold = {Threshold::Kind::FractionOfMax, 0.5};
  EXPECT_NE(text(v, roiReport(v, request, "tiny.nii", kNoNote))
                .find("  metabolic    0.016 ml  (2 voxels >= 2.5 Bq/ml, 50 % of max)\n"),
            std::string::npos);
}

TEST(RoiReport, SphereNamesItsCentreAndRadius) {
  const Volume v = indexVolume();
  RoiRequest request;
  request.sphere = SphereRoi{{2, 2, 0}, 2.5};  // voxel (1,1,0) and its 5 neighbours inside
  const RoiReport report = roiReport(v, request, "tiny.nii", kNoNote);
  ASSERT_EQ(report.rois.size(), 1u);
  EXPECT_EQ(report.rois[0].what, "sphere at 2.0, 2.0, 0.0 mm LPS, radius 2.5 mm");
  EXPECT_EQ(report.stats[0].voxels, 6u);
  EXPECT_DOUBLE_EQ(report.stats[0].mean, (5.0 + 4 + 6 + 1 + 9 + 21) / 6);
}

TEST(RoiReport, AnRoiOfOnlyNaNIsRefused) {
  Volume v = indexVolume();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) v.setValue(i, j, 0, 0, std::numeric_limits<double>::quiet_NaN());
  try {
    roiReport(v, boxRequest(), "given.nii", kNoNote);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("given.nii"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("holds no voxel with data (its 4 voxels are NaN)"),
              std::string::npos)
        << e.what();
  }
}

TEST(RoiReport, APetInBecquerelSaysWhy) {
  Volume v = indexVolume();
  v.metadata().modality = "PT";
  v.metadata().notes = {"values in Bq/ml: no SUV (the patient's weight is not stated)",
                        "another note"};
  std::vector<std::string> notes;
  roiReport(v, boxRequest(), "pet", [&](const std::string& n) { notes.push_back(n); });
  EXPECT_EQ(notes, std::vector<std::string>(
                       {"pet: values in Bq/ml: no SUV (the patient's weight is not stated)"}));
}

// Two label volumes' labels: 1 on the box, 2 on the voxel (3,3,3).
fs::path writeLabels(const fs::path& dir) {
  Volume labels({4, 4, 4}, 1, ScalarType::UInt8,
                makeWorldFromIndex(glm::dvec3(0.0), glm::dvec3(2.0), glm::dmat3(1.0)));
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) labels.setValue(i, j, 0, 0, 1);
  labels.setValue(3, 3, 3, 0, 2);
  const fs::path file = dir / "labels.nii";
  io::writeVolume(labels, file);
  return file;
}

TEST(RoiReport, EveryLabelOfALabelVolumeAndNoTotal) {
  const Volume v = indexVolume();
  RoiRequest request;
  request.labels = writeLabels(test::scratchDir());
  const RoiReport report = roiReport(v, request, "tiny.nii", kNoNote);
  ASSERT_EQ(report.rois.size(), 2u);
  EXPECT_EQ(report.rois[0].label->number, 1);
  EXPECT_TRUE(report.rois[0].gridsCoincide);
  EXPECT_EQ(report.stats[0].voxels, 4u);
  EXPECT_EQ(report.stats[1].max, 63.0);
  EXPECT_FALSE(report.total);  // a total follows a SEG's segments only
  const nlohmann::json j = roiReportJson(report);
  EXPECT_EQ(j[1]["label"], 2);
  EXPECT_EQ(j[1]["grids_coincide"], true);
}

TEST(RoiReport, AMissingLabelListsTheLabels) {
  const Volume v = indexVolume();
  RoiRequest request;
  request.labels = writeLabels(test::scratchDir());
  request.label = 7;
  try {
    roiReport(v, request, "tiny.nii", kNoNote);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no label 7 (2 labels: 1, 2)"), std::string::npos)
        << e.what();
  }
}

// A SEG of two boxes that share the voxels of value 1 and 5: A holds 0, 1, 4, 5 (max 5), B 1,
// 2, 5, 6 (max 6). At half their max, A keeps 4, 5 and B 5, 6: the total metabolic volume is
// the voxels 4, 5, 6 (0.024 ml, mean 5, TLG 0.12); the union holds 0, 1, 2, 4, 5, 6 (0.048 ml,
// max 6, mean 3).
TEST(RoiReport, TheSegmentsOfASegAndTheirTotal) {
  const Volume v = indexVolume();
  dicomout::SegmentMask a{"A", "", {0, 1, 4, 5}, false}, b{"B", "", {1, 2, 5, 6}, false};
  const fs::path file = test::scratchDir() / "two.dcm";
  dicomout::writeSegmentation(file, v, {a, b}, dicomout::identityOf(v, {"TEST-1", "Test^Seg"}),
                              {"", 3001, "test"}, "unit test");
  RoiRequest request;
  request.labels = file;
  request.threshold = {Threshold::Kind::FractionOfMax, 0.5};
  const RoiReport report = roiReport(v, request, "tiny.nii", kNoNote);
  ASSERT_EQ(report.rois.size(), 2u);
  EXPECT_EQ(report.rois[0].what, "label 1 \"A\"");
  ASSERT_TRUE(report.total);
  const std::string t = text(v, report);
  const std::string total =
      "total over the 2 segments\n"
      "  voxels       6  (0.048 ml)\n"
      "  max          6 Bq/ml\n"
      "  mean         3 Bq/ml\n"
      "  TMTV         0.024 ml  (3 voxels, each segment at its own threshold)\n"
      "  metab. mean  5 Bq/ml\n"
      "  TLG          0.12 Bq/ml x ml  (total metabolic tumour volume x its mean)\n";
  ASSERT_GE(t.size(), total.size());
  EXPECT_EQ(t.substr(t.size() - total.size()), total) << t;
  const nlohmann::json j = roiReportJson(report);
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[2]["total"], true);
  EXPECT_EQ(j[2]["segments"], 2);
  EXPECT_EQ(j[2]["voxels"], 6);
  EXPECT_EQ(j[2]["metabolic_voxels"], 3);
  EXPECT_DOUBLE_EQ(j[2]["metabolic_mean"].get<double>(), 5.0);
  EXPECT_NEAR(j[2]["tlg"].get<double>(), 0.12, 1e-15);
  // One segment asked for: no total.
  request.label = 2;
  EXPECT_FALSE(roiReport(v, request, "tiny.nii", kNoNote).total);
}

TEST(RoiReport, TheSegOfAMetabolicVolume) {
  const Volume v = indexVolume();
  RoiRequest request = boxRequest();
  request.threshold = {Threshold::Kind::Absolute, 4.0};
  const RoiSegmentation seg = roiSegmentation(v, roiReport(v, request, "tiny.nii", kNoNote));
  ASSERT_EQ(seg.segments.size(), 1u);
  EXPECT_EQ(seg.segments[0].label, "");  // the SEG labels it by its code
  EXPECT_EQ(seg.segments[0].description,
            "metabolic volume >= 4 Bq/ml in box 0.0, 0.0, 0.0 .. 2.0, 2.0, 0.0 mm LPS");
  EXPECT_EQ(seg.segments[0].voxels, VoxelList({4, 5}));
  EXPECT_TRUE(seg.segments[0].metabolic);
  EXPECT_EQ(seg.algorithm, "mvw stats, threshold 4 Bq/ml");
  EXPECT_EQ(seg.seriesDescription, "mvw metabolic volume >= 4 Bq/ml");
  request.threshold = {Threshold::Kind::FractionOfMax, 0.41};
  EXPECT_EQ(roiSegmentation(v, roiReport(v, request, "tiny.nii", kNoNote)).algorithm,
            "mvw stats, threshold 41 % of max");
}

TEST(RoiReport, TheSegOfRois) {
  const Volume v = indexVolume();
  RoiRequest request;
  request.labels = writeLabels(test::scratchDir());
  const RoiSegmentation seg = roiSegmentation(v, roiReport(v, request, "tiny.nii", kNoNote));
  ASSERT_EQ(seg.segments.size(), 2u);
  EXPECT_EQ(seg.segments[0].voxels, VoxelList({0, 1, 4, 5}));
  EXPECT_FALSE(seg.segments[0].metabolic);
  EXPECT_EQ(seg.segments[1].voxels, VoxelList({63}));
  EXPECT_EQ(seg.algorithm, "mvw stats, ROI");
  EXPECT_EQ(seg.seriesDescription, "mvw segmentation (2 segments)");
}

TEST(RoiReport, AStudyWithoutAFunctionalVolume) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(indexVolume(), dir / "ct.nii");
  std::ofstream(dir / "study.json") << R"({"anatomical": {"path": "ct.nii"}})";
  EXPECT_EQ(readMeasuredVolume(dir / "study.json", true, {}, {}).dimensions(), glm::ivec3(4));
  EXPECT_EQ(readMeasuredVolume(dir / "ct.nii", false, {}, {}).dimensions(), glm::ivec3(4));
  try {
    readMeasuredVolume(dir / "study.json", false, {}, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the study names no functional volume"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mvw::study
