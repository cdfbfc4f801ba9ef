// `mvw register`'s run (output::RegistrationRun): its names for the resampling choices, the
// output folder's checks, the identities of a DICOM output, registration.json from a known
// transform, its warning, and a whole run on two small synthetic volumes.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "RegistrationTestUtil.h"
#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/output/RegistrationRun.h"
#include "mvw/resampling/Transform.h"

namespace mvw::output {
namespace {

namespace fs = std::filesystem;
using resampling::Initialisation;
using resampling::Interpolation;
using resampling::RegistrationResult;

TEST(RegistrationRun, ResamplingAndInitialisationNamesRoundTrip) {
  for (const char* name : {"auto", "linear", "nearest", "cubic"}) {
    ASSERT_TRUE(parseInterpolation(name)) << name;
    EXPECT_EQ(interpolationName(*parseInterpolation(name)), name);
  }
  EXPECT_EQ(parseInterpolation("Linear"), std::nullopt);
  EXPECT_EQ(parseInitialisation("world"), Initialisation::WorldCoordinates);
  EXPECT_EQ(parseInitialisation("centre"), Initialisation::GeometricCentre);
  EXPECT_EQ(parseInitialisation("mass"), Initialisation::CentreOfMass);
  EXPECT_EQ(parseInitialisation("auto"), Initialisation::Automatic);
  EXPECT_EQ(parseInitialisation("center"), std::nullopt);
}

TEST(RegistrationRun, TheOutputFolderIsAFolderWhoseParentExists) {
  const fs::path dir = test::scratchDir();
  EXPECT_NO_THROW(checkRegistrationFolder(dir / "new"));
  EXPECT_NO_THROW(checkRegistrationFolder((dir / "new/").string()));
  EXPECT_NO_THROW(checkRegistrationFolder(dir));
  EXPECT_FALSE(fs::exists(dir / "new"));  // the check makes nothing
  std::ofstream(dir / "file") << "x";
  try {
    checkRegistrationFolder(dir / "file");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "exists and is not a folder");
  }
  try {
    checkRegistrationFolder(dir / "missing" / "out");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "its parent folder does not exist");
  }
}

// A volume read from a file that is not DICOM (no identity of its own).
Volume notDicom(const std::string& path) {
  Volume v = resampling::blobs({0, 0, 0});
  v.metadata().format = "NIfTI-1";
  v.metadata().sourcePath = path;
  return v;
}

TEST(RegistrationRun, AMovingVolumeThatIsNotDicomJoinsTheFixedOnesPatient) {
  const Volume fixed = notDicom("ct.nii"), moving = notDicom("pet.nii");
  const RegistrationIdentities ids = registrationIdentities(fixed, moving, {"P-17", "Doe^J"});
  EXPECT_EQ(ids.fixed.patientId, "P-17");
  EXPECT_EQ(ids.moving.patientId, "P-17");
  EXPECT_EQ(ids.moving.patientName, "Doe^J");
  // Without an identity, the fixed source is refused before any registration.
  EXPECT_THROW(registrationIdentities(fixed, moving, {}), InputError);
  EXPECT_THROW(registrationIdentities(fixed, moving, {"P-17", ""}), InputError);
}

// A rigid result about a centre, as registerRigid reports one: 2 levels, 4 runs.
RegistrationResult knownResult() {
  RegistrationResult r;
  r.parameters = {{0.1, -0.05, 0.2}, {3.0, -2.0, 1.5}};
  const glm::dvec3 centre(10.0, 20.0, -30.0);
  r.transform = resampling::Transform::fromMovingFromFixed(
      resampling::rigidMatrix(r.parameters, centre), centre);
  r.initialisation = Initialisation::GeometricCentre;
  r.initialTranslationMm = {1.0, 2.0, 3.0};
  r.runs = 4;
  r.runsAveraged = 3;
  r.iterations = 57;
  r.converged = true;
  r.seconds = 1.25;
  resampling::LevelReport level;
  level.smoothingMm = 4.0;
  level.fixedDimensions = {20, 19, 18};
  level.movingDimensions = {10, 9, 8};
  level.samples = 4000;
  level.validSamples = 3900;
  level.iterations = 40;
  level.metricStart = 0.3;
  level.metricEnd = 0.6;
  level.finalStepMm = 0.004;
  level.converged = true;
  level.seconds = 0.5;
  r.levels = {level};
  return r;
}

RegistrationRecord knownRecord() {
  RegistrationRecord record;
  record.fixedName = "ct.nii.gz";
  record.movingName = "pet.nii.gz";
  record.seed = 7;
  record.interpolation = Interpolation::Linear;
  record.outputs = {"transform.tfm", "registration.json"};
  return record;
}

TEST(RegistrationRun, TheReportGivesTheTransformItsParametersAndTheLevels) {
  const RegistrationResult r = knownResult();
  const nlohmann::json j = registrationJson(r, knownRecord());
  EXPECT_EQ(j["fixed"], "ct.nii.gz");
  EXPECT_EQ(j["moving"], "pet.nii.gz");
  EXPECT_FALSE(j.contains("study"));
  EXPECT_FALSE(j.contains("rotation_search"));
  EXPECT_EQ(j["method"], "rigid, Mattes mutual information, quasi-Newton (BFGS) ascent");
  EXPECT_EQ(j["runs"], 4);
  EXPECT_EQ(j["runs_averaged"], 3);
  EXPECT_EQ(j["sample_points_in"], "fixed");
  EXPECT_EQ(j["initialisation"], "geometric centre");
  EXPECT_EQ(j["initial_translation_mm"], nlohmann::json({1.0, 2.0, 3.0}));
  EXPECT_EQ(j["seed"], 7);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["iterations"], 57);
  EXPECT_EQ(j["seconds"], 1.25);
  EXPECT_EQ(j["warnings"], nlohmann::json::array());
  ASSERT_EQ(j["levels"].size(), 1u);
  EXPECT_EQ(j["levels"][0]["stage"], "rigid");
  EXPECT_EQ(j["levels"][0]["moving_dimensions"], nlohmann::json({10, 9, 8}));
  EXPECT_EQ(j["levels"][0]["mutual_information_end"], 0.6);
  EXPECT_EQ(j["affine"], false);
  const nlohmann::json& p = j["parameters"];
  EXPECT_EQ(p["convention"], "moving = R (fixed - centre) + centre + translation, R = Rz Rx Ry");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(p["angles_rad"][k].get<double>(), r.parameters.angles[k], 1e-12);
    EXPECT_NEAR(p["angles_deg"][k].get<double>(), r.parameters.angles[k] * 180.0 / std::numbers::pi,
                1e-9);
    EXPECT_EQ(p["translation_mm"][k].get<double>(), r.parameters.translation[k]);
  }
  EXPECT_EQ(p["centre_mm"], nlohmann::json({10.0, 20.0, -30.0}));
  // The matrices row by row: fixed_from_moving's last column is its translation.
  const glm::dmat4& f = r.transform.fixedFromMoving();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      EXPECT_EQ(j["fixed_from_moving"][row][col].get<double>(), f[col][row]);
      EXPECT_EQ(j["moving_from_fixed"][row][col].get<double>(),
                r.transform.movingFromFixed()[col][row]);
    }
  EXPECT_EQ(j["interpolation"], "linear");
  EXPECT_EQ(j["outputs"], nlohmann::json({"transform.tfm", "registration.json"}));
}

TEST(RegistrationRun, AStudyASearchAndAnAffineStageAreSaid) {
  RegistrationResult r = knownResult();
  r.affine = true;
  r.searchedRotations = 343;
  r.searchAngles = {0.0, std::numbers::pi / 6, 0.0};
  r.samplesInMoving = true;
  RegistrationRecord record = knownRecord();
  record.studyPath = "study.json";
  record.rotationSearchRangeDeg = 90.0;
  const nlohmann::json j = registrationJson(r, record);
  EXPECT_EQ(j["study"], "study.json");
  EXPECT_EQ(j["method"],
            "rigid then affine, Mattes mutual information, quasi-Newton (BFGS) ascent");
  EXPECT_EQ(j["affine"], true);
  EXPECT_EQ(j["sample_points_in"], "moving (its box is under half the fixed one's)");
  EXPECT_EQ(j["rotation_search"]["range_deg"], 90.0);
  EXPECT_EQ(j["rotation_search"]["rotations_scored"], 343);
  EXPECT_NEAR(j["rotation_search"]["best_angles_deg"][1].get<double>(), 30.0, 1e-12);
}

// After a rotation search the optimiser may hold (-180, -180, 180) degrees for no rotation;
// the report gives ITK's decomposition of the same matrix.
TEST(RegistrationRun, TheAnglesAreItksDecompositionOfTheSameRotation) {
  RegistrationResult r = knownResult();
  r.parameters.angles = {-std::numbers::pi, -std::numbers::pi, std::numbers::pi};
  const glm::dvec3 angles = registrationAngles(r);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(angles[k], 0.0, 1e-9);
  const nlohmann::json j = registrationJson(r, knownRecord());
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(j["parameters"]["angles_deg"][k].get<double>(), 0.0, 1e-7);
}

TEST(RegistrationRun, AFinalMutualInformationNearZeroIsAWarning) {
  RegistrationResult r = knownResult();
  EXPECT_TRUE(registrationWarnings(r).empty());
  r.levels.back().metricEnd = 0.00437;
  const auto warnings = registrationWarnings(r);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "the mutual information at the end is 0.0044 (below 0.01): the volumes share almost no "
            "structure, so the transform is not determined by them; check registration_qa.png");
  r.levels.clear();
  EXPECT_TRUE(registrationWarnings(r).empty());
}

// Two small volumes as files, 3 mm apart: the results in place, nothing else left, and what
// the run said.
TEST(RegistrationRun, ARunWritesEveryResultAndSaysWhatItWrote) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(resampling::blobs({0, 0, 0}), dir / "fixed.nii.gz");
  io::writeVolume(resampling::blobs({3, 0, 0}), dir / "moving.nii.gz");
  RegistrationRequest request;
  request.fixed = (dir / "fixed.nii.gz").string();
  request.moving = (dir / "moving.nii.gz").string();
  request.output = dir / "out";
  request.options.runs = 1;
  request.options.samples = {3000};
  request.options.smoothingMm = {4.0, 0.0};
  std::ostringstream out, err;
  const RegistrationOutcome outcome = runRegistration(request, out, err);
  EXPECT_TRUE(outcome.dicomFiles.empty());
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir / "out"))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"functional_on_anatomical.nii.gz", "registration.json",
                                             "registration_qa.png", "transform.tfm"}));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
  std::ifstream in(dir / "out" / "registration.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["fixed"], request.fixed);
  EXPECT_EQ(j["interpolation"], "linear");
  // The moving volume's blobs lie 3 mm further along x: fixed = moving - 3 mm.
  EXPECT_NEAR(j["fixed_from_moving"][0][3].get<double>(), -3.0, 0.3);
  const std::string said = out.str();
  EXPECT_EQ(said.rfind("registered " + request.moving + " to " + request.fixed + " in ", 0), 0u)
      << said;
  EXPECT_NE(
      said.find("  wrote " + (request.output / "transform.tfm").string() + ", " +
                (request.output / "functional_on_anatomical.nii.gz").string() + " (linear), "),
      std::string::npos)
      << said;
  EXPECT_EQ(err.str(), "");
}

TEST(RegistrationRun, AnInputThatCannotBeReadLeavesNoOutput) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(resampling::blobs({0, 0, 0}), dir / "fixed.nii.gz");
  RegistrationRequest request;
  request.fixed = (dir / "fixed.nii.gz").string();
  request.moving = (dir / "missing.nii.gz").string();
  request.output = dir / "out";
  std::ostringstream out, err;
  EXPECT_THROW(runRegistration(request, out, err), InputError);
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_EQ(out.str(), "");
}

TEST(RegistrationRun, AStudyWithoutAFunctionalVolumeIsRefused) {
  const fs::path dir = test::scratchDir();
  io::writeVolume(resampling::blobs({0, 0, 0}), dir / "ct.nii.gz");
  std::ofstream(dir / "study.json") << R"({"anatomical": {"path": "ct.nii.gz"}})";
  std::ostringstream err;
  try {
    loadRegistrationStudy((dir / "study.json").string(), false, err);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), "the study names no functional volume: nothing to register");
  }
  EXPECT_EQ(err.str(), "");
}

}  // namespace
}  // namespace mvw::output
