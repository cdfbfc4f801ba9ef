// `mvw convert`'s pieces (study::VolumeConversion): the sidecar's name and contents, what is
// refused about the output before anything is read, the frame choice, one volume of a study
// config, and both files written together with the line that says so.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/study/VolumeConversion.h"

namespace mvw::study {
namespace {

namespace fs = std::filesystem;

// A small 4D volume (2 frames), as a NIfTI file holds one.
Volume fourD() {
  Volume v({4, 3, 2}, 2, ScalarType::Int16,
           makeWorldFromIndex({-1, -2, -3}, {1.5, 1.5, 2}, glm::dmat3(1.0)));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) {
        v.setValue(i, j, k, 0, i + j + k);
        v.setValue(i, j, k, 1, 10 * (i + j + k));
      }
  v.metadata().unit = "Bq/ml";
  return v;
}

ConversionRequest requestOf(const std::string& input, const fs::path& output,
                            const std::string& volume = "") {
  ConversionRequest request;
  request.input = input;
  request.output = output;
  request.volume = volume;
  return request;
}

TEST(VolumeConversion, TheSidecarIsNamedAfterTheOutputAsDcm2niixNamesIt) {
  EXPECT_EQ(sidecarOf("out/ct.nii.gz"), fs::path("out/ct.json"));
  EXPECT_EQ(sidecarOf("ct.nii"), fs::path("ct.json"));
  EXPECT_EQ(sidecarOf("/tmp/x.y.mha"), fs::path("/tmp/x.y.json"));
  EXPECT_EQ(sidecarOf("out/.nii.gz"), fs::path());  // the extension alone
  EXPECT_EQ(sidecarOf("ct.png"), fs::path());
  EXPECT_EQ(sidecarOf("ct.NII"), fs::path());
  EXPECT_TRUE(isStudyConfig("a/study.json"));
  EXPECT_FALSE(isStudyConfig("a/ct.nii.gz"));
}

std::string problemOf(const ConversionRequest& request) {
  try {
    checkConversionOutput(request);
  } catch (const InputError& e) {
    return e.file().filename().string() + ": " + e.problem();
  }
  return "";
}

TEST(VolumeConversion, AnOutputThatCannotBeWrittenIsRefusedBeforeTheInputIsRead) {
  const fs::path dir = test::scratchDir();
  ConversionRequest request = requestOf((dir / "missing.nii").string(), dir / "out.png");
  EXPECT_EQ(problemOf(request), "out.png: unknown output format (use .nii.gz, .nii or .mha)");
  request.output = dir / "out.nii.gz";
  EXPECT_EQ(checkConversionOutput(request), dir / "out.json");
  fs::create_directories(dir / "out.json");
  EXPECT_EQ(problemOf(request), "out.json: the sidecar's name is taken by a folder");
  fs::remove(dir / "out.json");
  std::ofstream(dir / "out.json") << R"({"name": "a study"})";
  EXPECT_EQ(problemOf(request),
            "out.json: the sidecar's name is taken by a file mvw convert did not write; move it "
            "or choose another output name");
  std::ofstream(dir / "out.json") << R"({"written_by": "mvw convert"})";
  EXPECT_EQ(problemOf(request), "");  // an earlier convert's sidecar is replaced
  // The input's own name as the sidecar's.
  std::ofstream(dir / "in.json") << "{}";
  request.input = (dir / "in.json").string();
  request.output = dir / "in.nii";
  EXPECT_EQ(problemOf(request),
            "in.json: the sidecar's name is the input's: choose another output name");
}

TEST(VolumeConversion, TheSidecarSaysWhereTheValuesCameFrom) {
  Volume v = fourD();
  v.metadata().seriesDescription = "PET AC";
  v.metadata().seriesNumber = 4;
  v.metadata().seriesInstanceUid = "1.2.3";
  v.metadata().suvFactor = 0.5;
  const nlohmann::json description = {
      {"path", "/data/pet"}, {"format", "DICOM"}, {"unit", "SUVbw"}};
  ConversionRequest request = requestOf("data/../pet", "pet.nii.gz");
  nlohmann::json j = conversionSidecar(description, v, request);
  EXPECT_FALSE(j.contains("path"));
  EXPECT_EQ(j["format"], "DICOM");
  EXPECT_EQ(j["unit"], "SUVbw");
  EXPECT_EQ(j["source_path"], (fs::current_path() / "pet").string());
  EXPECT_EQ(j["series_description"], "PET AC");
  EXPECT_EQ(j["series_number"], 4);
  EXPECT_EQ(j["series_instance_uid"], "1.2.3");
  EXPECT_EQ(j["suv_factor"], 0.5);
  EXPECT_EQ(j["frame"], "all");
  EXPECT_FALSE(j.contains("study_volume"));
  EXPECT_EQ(j["written_by"], "mvw convert");
  request.frame = "mean";
  EXPECT_EQ(conversionSidecar(description, v, request)["frame"], "mean");
  request = requestOf("study.json", "pet.nii.gz", "functional");
  v.metadata().suvFactor.reset();
  j = conversionSidecar(description, v, request);
  EXPECT_EQ(j["study_volume"], "functional");
  EXPECT_EQ(j["frame"], "as the study config reads it");
  EXPECT_FALSE(j.contains("suv_factor"));
  request.volume = "";
  EXPECT_EQ(conversionSidecar(description, v, request)["study_volume"], "anatomical");
}

TEST(VolumeConversion, AFrameIsANumberOrMean) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(fourD(), dir / "pet.nii.gz");
  ConversionRequest request = requestOf((dir / "pet.nii.gz").string(), dir / "out.nii");
  EXPECT_EQ(readConversionInput(request, {}).components(), 2);
  request.frame = "1";
  const Volume second = readConversionInput(request, {});
  EXPECT_EQ(second.components(), 1);
  EXPECT_EQ(second.value(3, 2, 1, 0), 60.0);
  request.frame = "last";
  try {
    readConversionInput(request, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "--frame 'last' must be a frame number (0, 1, ...) or 'mean'");
  }
}

TEST(VolumeConversion, AStudyVolumeTheStudyDoesNotNameIsRefused) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(fourD(), dir / "ct.nii.gz");
  std::ofstream(dir / "study.json") << R"({"anatomical": {"path": "ct.nii.gz"}})";
  const std::string study = (dir / "study.json").string();
  EXPECT_EQ(readStudyVolume(study, "", {}, {}).dimensions(), glm::ivec3(4, 3, 2));
  EXPECT_EQ(readStudyVolume(study, "anatomical", {}, {}).dimensions(), glm::ivec3(4, 3, 2));
  try {
    readStudyVolume(study, "functional", {}, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "the study names no functional volume (--volume functional)");
  }
  try {
    readStudyVolume(study, "segmentation", {}, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "the study names no segmentation (--volume segmentation)");
  }
}

TEST(VolumeConversion, BothFilesAreWrittenAndSaid) {
  const fs::path dir = test::scratchDir();
  const Volume v = fourD();
  writeConversion(v, dir / "pet.nii.gz", dir / "pet.json", "{}\n");
  EXPECT_EQ(io::readVolume(dir / "pet.nii.gz").components(), 2);
  std::ifstream in(dir / "pet.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "{}\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
  ConversionRequest request = requestOf("pet.nii", "out/pet.nii.gz");
  EXPECT_EQ(conversionSummary(v, request, "out/pet.json"),
            "wrote out/pet.nii.gz (4 x 3 x 2 x 2 frames, int16, Bq/ml) and out/pet.json\n");
  request = requestOf("study.json", "ct.nii");
  EXPECT_EQ(
      conversionSummary(v, request, "ct.json"),
      "wrote ct.nii (4 x 3 x 2 x 2 frames, int16, Bq/ml) and ct.json: the anatomical volume of "
      "study.json (--volume functional|segmentation for the others)\n");
  request.volume = "functional";
  EXPECT_EQ(
      conversionSummary(v, request, "ct.json"),
      "wrote ct.nii (4 x 3 x 2 x 2 frames, int16, Bq/ml) and ct.json: the functional volume of "
      "study.json\n");
}

TEST(VolumeConversion, AFolderThatCannotBeWrittenIsBadInput) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "file") << "x";
  try {
    writeConversion(fourD(), dir / "file" / "pet.nii", dir / "file" / "pet.json", "{}\n");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), dir / "file");  // the folder the output names
  }
}

}  // namespace
}  // namespace mvw::study
