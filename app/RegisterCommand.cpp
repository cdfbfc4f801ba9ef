#include "RegisterCommand.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "DicomOutput.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/dicomout/SpatialRegistration.h"
#include "mvw/dicomout/VolumeSeries.h"
#include "mvw/io/Png.h"
#include "mvw/io/StagedFolder.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/resampling/RegistrationQa.h"
#include "mvw/resampling/Resample.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"
#include "mvw/study/FunctionalPlacement.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::app {

namespace {

// Below this final MI (nats) a registration is reported as undetermined (a warning): the
// CT / PET-like pairs of the tests end near 1.0, the real T1 / CBF pair at 0.44, the nipy
// T1 / fMRI pair at 0.22.
constexpr double kWeakMutualInformation = 0.01;

namespace fs = std::filesystem;
using namespace mvw::resampling;

struct RegisterOptions {
  std::string study;  // a study config: its anatomical (fixed) and functional (moving) volumes
  std::string fixed, moving, output;
  std::string fixedSeries, movingSeries;
  std::string interpolation = "auto";
  std::string initialisation = "auto";
  std::uint64_t seed = RegistrationOptions{}.seed;
  bool noSuv = false;
  bool affine = false;
  double rotationSearchDeg = 0.0;
  DicomOutputOptions dicom;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

const std::map<std::string, Interpolation> kInterpolations = {{"auto", Interpolation::Automatic},
                                                              {"linear", Interpolation::Linear},
                                                              {"nearest", Interpolation::Nearest},
                                                              {"cubic", Interpolation::Cubic}};
const std::map<std::string, Initialisation> kInitialisations = {
    {"auto", Initialisation::Automatic},
    {"world", Initialisation::WorldCoordinates},
    {"centre", Initialisation::GeometricCentre},
    {"mass", Initialisation::CentreOfMass}};

std::string name(Interpolation i) {
  for (const auto& [k, v] : kInterpolations)
    if (v == i) return k;
  return "?";
}

nlohmann::json rows(const glm::dmat4& m) {
  auto j = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) j.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return j;
}

nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
nlohmann::json vec(const glm::ivec3& v) { return {v.x, v.y, v.z}; }

// Refused before any heavy work: the output folder is made if missing, its parent is not.
void checkOutputFolder(const fs::path& output) {
  std::error_code ec;
  if (fs::exists(output, ec) && !fs::is_directory(output, ec))
    throw InputError(output, "exists and is not a folder");
  fs::path absolute = fs::absolute(output);
  if (!absolute.has_filename()) absolute = absolute.parent_path();  // "out/" names "out"
  if (!fs::is_directory(absolute.parent_path(), ec))
    throw InputError(absolute, "its parent folder does not exist");
}

// The two volumes: the files given, or a study config's anatomical and functional volumes read
// as every command reads the study (their series, "frame", PACS series from the cache).
struct Inputs {
  Volume fixed, moving;
  std::string fixedName, movingName;  // as the outputs name them
};

Inputs readInputs(const RegisterOptions& opt,
                  const std::optional<config::StudyConfig>& studyConfig) {
  Inputs in;
  io::ReadOptions fixedRead, movingRead;
  fixedRead.suv = movingRead.suv = !opt.noSuv;
  if (studyConfig) {
    in.fixed = study::readAnatomical(studyConfig->anatomical, fixedRead, opt.pacs);
    in.moving = study::readFunctional(*studyConfig, movingRead, opt.pacs);
    in.fixedName = opt.study + " (anatomical)";
    in.movingName = opt.study + " (functional)";
    return in;
  }
  fixedRead.series = opt.fixedSeries;
  movingRead.series = opt.movingSeries;
  in.fixed = io::readVolume(opt.fixed, fixedRead);
  in.moving = io::readVolume(opt.moving, movingRead);
  in.fixedName = opt.fixed;
  in.movingName = opt.moving;
  return in;
}

void runRegister(RegisterOptions opt, const CLI::App& cmd) {
  // STUDY.json, or --fixed and --moving: one of the two.
  std::optional<config::StudyConfig> studyConfig;
  // The study's registration settings (study::registrationOptionsOf, as placing the study and
  // the viewer's re-run map them), then the command line's over them.
  RegistrationOptions options;
  if (!opt.study.empty()) {
    for (const char* o : {"--fixed", "--moving", "--fixed-series", "--moving-series"})
      if (cmd.count(o))
        throw CLI::ValidationError(o, std::string("names a volume; the study config ") + opt.study +
                                          " names both: give one or the other");
    if (fs::path(opt.study).extension() != ".json")
      throw CLI::ValidationError("STUDY", "'" + opt.study +
                                              "' is not a study config (.json): give the "
                                              "volumes with --fixed and --moving");
    studyConfig = config::loadStudyConfig(opt.study);
    if (!studyConfig->functional)
      throw InputError(opt.study, "the study names no functional volume: nothing to register");
    const config::RegistrationConfig& r = studyConfig->registration;
    options = study::registrationOptionsOf(r);
    if (r.method == config::RegistrationMethod::File)
      std::cerr << "mvw register: note: the study places its functional volume by "
                << r.transform.string() << "; registering anew (rigid"
                << (opt.affine ? " then affine" : "") << ")\n";
  } else if (opt.fixed.empty() || opt.moving.empty()) {
    throw CLI::ValidationError(opt.fixed.empty() ? "--fixed" : "--moving",
                               "is required (or give a study config: mvw register STUDY.json "
                               "-o OUT)");
  }
  const auto interpolation = kInterpolations.at(opt.interpolation);
  // Checked before any heavy work: a wrong -o should not cost a registration.
  checkDicomOutput(opt.dicom, opt.dicom.dicom, opt.output);
  checkOutputFolder(opt.output);
  // Everything is written into a staging folder first and moved into place at the end, so a
  // failure at any step leaves no partial result in the output folder.
  io::StagedFolder staging(opt.output, {.purpose = "register"});

  Inputs inputs = readInputs(opt, studyConfig);
  Volume fixed = std::move(inputs.fixed);
  const Volume moving = std::move(inputs.moving);
  // With --dicom, the identities before the registration: a source without one is refused
  // now. A moving volume that is not DICOM joins the fixed one's patient and study.
  std::optional<dicomout::DicomIdentity> fixedId, movingId;
  if (opt.dicom.dicom) {
    fixedId = dicomout::identityOf(fixed, opt.dicom.given());
    dicomout::GivenIdentity movingGiven = opt.dicom.given();
    if (moving.metadata().format != "DICOM") {
      if (movingGiven.patientId.empty()) movingGiven.patientId = fixedId->patientId;
      if (movingGiven.patientName.empty())
        movingGiven.patientName =
            fixedId->patientName.empty() ? fixedId->patientId : fixedId->patientName;
    }
    movingId = dicomout::identityOf(moving, movingGiven);
  }

  options.seed = opt.seed;
  options.initialisation = kInitialisations.at(opt.initialisation);
  if (opt.affine) options.affine = true;
  if (cmd.count("--rotation-search")) options.rotationSearchRangeDeg = opt.rotationSearchDeg;
  if (::isatty(STDERR_FILENO))
    options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const RegistrationResult r = registerRigid(fixed, moving, options);

  ResampleOptions resampleOptions;
  resampleOptions.interpolation = interpolation;
  const Interpolation used = chosenInterpolation(moving, resampleOptions);
  // Before: the volumes as their headers place them in the world.
  io::writePng(registrationQaImage(fixed, moving, Transform(), r.transform),
               staging.path() / "registration_qa.png");
  const Grid grid = gridOf(fixed);
  fixed = Volume();  // only its grid is needed from here: the peak memory is the output's
  const Volume onGrid = resample(moving, grid, r.transform, resampleOptions);

  r.transform.writeItk(staging.path() / "transform.tfm");
  io::writeVolume(onGrid, staging.path() / "functional_on_anatomical.nii.gz");
  std::vector<std::string> dicomOutputs;
  std::string seriesNote;
  if (fixedId) {
    dicomout::SeriesInfo regSeries;
    regSeries.seriesNumber = 2001;
    regSeries.description = "mvw registration (" + std::string(r.affine ? "affine" : "rigid") + ")";
    dicomout::writeSpatialRegistration(staging.path() / "registration.dcm", *fixedId, *movingId,
                                       r.transform.fixedFromMoving(), r.affine, regSeries,
                                       std::string(r.affine ? "rigid then affine" : "rigid") +
                                           ", Mattes mutual information (mvw register)");
    dicomOutputs.push_back("registration.dcm");
    dicomout::SeriesInfo resampled;
    resampled.seriesNumber = 2002;
    resampled.description =
        (moving.metadata().seriesDescription.empty() ? std::string("functional")
                                                     : moving.metadata().seriesDescription) +
        " on the anatomical grid";
    try {
      const int files = dicomout::writeVolumeSeries(
          staging.path() / "functional_on_anatomical", onGrid, *movingId, *fixedId, resampled,
          "resampled onto the grid of " + inputs.fixedName + " by mvw register (" + name(used) +
              ")");
      dicomOutputs.push_back("functional_on_anatomical");
      seriesNote = "functional_on_anatomical/ (" + std::to_string(files) + " " +
                   movingId->modality + " images)";
    } catch (const InputError& e) {
      // A functional source that is not a DICOM PT, MR or CT series: the registration object
      // is written, the series is not, and the reader is told why.
      seriesNote = std::string("no DICOM series of the resampled volume: ") + e.what();
    }
  }

  nlohmann::json j;
  j["fixed"] = inputs.fixedName;
  j["moving"] = inputs.movingName;
  if (!opt.study.empty()) j["study"] = opt.study;
  j["method"] = std::string(r.affine ? "rigid then affine" : "rigid") +
                ", Mattes mutual information, quasi-Newton (BFGS) ascent";
  if (r.searchedRotations > 0)
    j["rotation_search"] = {{"range_deg", options.rotationSearchRangeDeg},
                            {"rotations_scored", r.searchedRotations},
                            {"best_angles_deg", vec(r.searchAngles * (180.0 / std::numbers::pi))}};
  j["runs"] = r.runs;
  j["runs_averaged"] = r.runsAveraged;
  j["sample_points_in"] =
      r.samplesInMoving ? "moving (its box is under half the fixed one's)" : "fixed";
  j["initialisation"] = toString(r.initialisation);
  j["initial_translation_mm"] = vec(r.initialTranslationMm);
  j["seed"] = opt.seed;
  j["converged"] = r.converged;
  j["iterations"] = r.iterations;
  j["seconds"] = r.seconds;
  // A final mutual information near 0: the volumes share next to no structure (one of them
  // nearly constant, or not the same anatomy), and any transform scores about the same. The
  // registration "converges" there all the same, so it is said, not left to the QA image.
  std::vector<std::string> warnings;
  if (!r.levels.empty() && r.levels.back().metricEnd < kWeakMutualInformation) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "the mutual information at the end is %.2g (below %g): the volumes share "
                  "almost no structure, so the transform is not determined by them; check "
                  "registration_qa.png",
                  r.levels.back().metricEnd, kWeakMutualInformation);
    warnings.push_back(text);
  }
  j["warnings"] = warnings;
  j["levels"] = nlohmann::json::array();
  for (const auto& l : r.levels)
    j["levels"].push_back({{"stage", l.stage},
                           {"smoothing_mm", l.smoothingMm},
                           {"fixed_dimensions", vec(l.fixedDimensions)},
                           {"moving_dimensions", vec(l.movingDimensions)},
                           {"samples", l.samples},
                           {"valid_samples", l.validSamples},
                           {"iterations", l.iterations},
                           {"rejected_steps", l.rejectedSteps},
                           {"mutual_information_start", l.metricStart},
                           {"mutual_information_end", l.metricEnd},
                           {"final_step_mm", l.finalStepMm},
                           {"converged", l.converged},
                           {"seconds", l.seconds}});
  // The angles in ITK's own decomposition (x within +-90 degrees): the optimiser's may be an
  // equivalent triple such as (-180, -180, 180) for no rotation at all (after a rotation
  // search), which reads as a large rotation. The same matrix; the translation is unchanged.
  const resampling::RigidParameters shown = resampling::rigidParameters(
      resampling::rigidMatrix(r.parameters, r.transform.centre()), r.transform.centre());
  const glm::dvec3 degrees = shown.angles * (180.0 / std::numbers::pi);
  // The parameters describe movingFromFixed (ITK's direction), about the centre; with
  // --affine they are the rigid stage's, and the matrices below the final affine map.
  j["affine"] = r.affine;
  j["parameters"] = {
      {"convention", "moving = R (fixed - centre) + centre + translation, R = Rz Rx Ry"},
      {"angles_rad", vec(shown.angles)},
      {"angles_deg", vec(degrees)},
      {"translation_mm", vec(r.parameters.translation)},
      {"centre_mm", vec(r.transform.centre())}};
  j["fixed_from_moving"] = rows(r.transform.fixedFromMoving());
  j["moving_from_fixed"] = rows(r.transform.movingFromFixed());
  j["interpolation"] = name(used);
  std::vector<std::string> outputs = {"transform.tfm", "functional_on_anatomical.nii.gz",
                                      "registration_qa.png", "registration.json"};
  outputs.insert(outputs.end(), dicomOutputs.begin(), dicomOutputs.end());
  j["outputs"] = outputs;
  {
    std::ofstream out(staging.path() / "registration.json");
    out << j.dump(2) << "\n";
    if (!out) throw Error((staging.path() / "registration.json").string() + ": cannot write");
  }
  staging.commit(outputs);

  std::cout << (r.affine ? "registered (rigid + affine) " : "registered ") << inputs.movingName
            << " to " << inputs.fixedName << " in " << r.seconds << " s, " << r.iterations
            << " iterations" << (r.converged ? "" : " (NOT converged)") << "\n"
            << "  rotation " << degrees.x << ", " << degrees.y << ", " << degrees.z
            << " deg, translation " << r.parameters.translation.x << ", "
            << r.parameters.translation.y << ", " << r.parameters.translation.z << " mm\n"
            << "  wrote " << (fs::path(opt.output) / "transform.tfm").string() << ", "
            << (fs::path(opt.output) / "functional_on_anatomical.nii.gz").string() << " ("
            << name(used) << "), " << (fs::path(opt.output) / "registration_qa.png").string()
            << ", " << (fs::path(opt.output) / "registration.json").string() << "\n";
  if (fixedId)
    std::cout << "  DICOM: " << (fs::path(opt.output) / "registration.dcm").string()
              << " (Spatial Registration, " << (r.affine ? "AFFINE" : "RIGID") << "), "
              << seriesNote << ", " << identityNote(*fixedId) << "\n";
  for (const std::string& w : warnings) std::cerr << "mvw register: warning: " << w << "\n";
  // Once everything is written and in place: the REG and the resampled series.
  if (fixedId) {
    std::vector<fs::path> written;
    for (const std::string& name : dicomOutputs) written.push_back(fs::path(opt.output) / name);
    storeDicom(opt.dicom, opt.pacs, written, opt.output, std::cout);
  }
}

}  // namespace

void addRegisterCommand(CLI::App& app, const pacs::Options& pacs) {
  auto opt = std::make_shared<RegisterOptions>();
  CLI::App* cmd = app.add_subcommand(
      "register",
      "Register a functional volume to an anatomical one (rigid, optionally affine) and resample "
      "it onto its grid; or a study config's functional volume to its anatomical one");
  cmd->add_option("study", opt->study,
                  "Study config (.json): its anatomical (fixed) and functional (moving) volumes "
                  "and its \"registration\" settings (affine, rotation_search_deg); instead of "
                  "--fixed and --moving");
  cmd->add_option("--fixed", opt->fixed,
                  "Anatomical (reference) volume: DICOM folder or file, NIfTI, MetaImage");
  cmd->add_option("--moving", opt->moving, "Functional volume to align");
  cmd->add_option("-o,--output", opt->output, "Output folder (created if missing)")
      ->required()
      ->check(nonEmpty());
  cmd->add_option("--fixed-series", opt->fixedSeries,
                  "DICOM series of the fixed volume: UID, number or description")
      ->check(nonEmpty());
  cmd->add_option("--moving-series", opt->movingSeries, "DICOM series of the moving volume")
      ->check(nonEmpty());
  cmd->add_option("--interpolation", opt->interpolation,
                  "Resampling: auto (nearest for label maps, else linear), linear, nearest, cubic")
      ->check(CLI::IsMember({"auto", "linear", "nearest", "cubic"}));
  cmd->add_option("--init", opt->initialisation,
                  "Initialisation: auto, world (headers as they are), centre (bounding boxes), "
                  "mass (centroids)")
      ->check(CLI::IsMember({"auto", "world", "centre", "mass"}));
  cmd->add_option("--seed", opt->seed, "Seed of the sample points (same seed, same result)")
      ->check(nonNegative());  // CLI11 would wrap -3 into an unsigned seed
  cmd->add_flag(
      "--affine", opt->affine,
      "After the rigid stage, an affine one (12 degrees of freedom: scaling and shear too)");
  cmd->add_option("--rotation-search", opt->rotationSearchDeg,
                  "Before refining, score rotations up to this many degrees about each axis in "
                  "30-degree steps on the coarsest level (for large misalignment); 0: off")
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_flag("--no-suv", opt->noSuv, "Keep PET values in Bq/ml instead of converting to SUVbw");
  addDicomOptions(*cmd, opt->dicom, true);
  cmd->callback([opt, cmd, &pacs] {
    opt->pacs = pacs;
    runRegister(*opt, *cmd);
  });
}

}  // namespace mvw::app
