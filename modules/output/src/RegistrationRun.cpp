#include "mvw/output/RegistrationRun.h"

#include <fstream>
#include <map>
#include <numbers>
#include <ostream>
#include <utility>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/dicomout/SpatialRegistration.h"
#include "mvw/dicomout/VolumeSeries.h"
#include "mvw/io/Png.h"
#include "mvw/io/StagedFolder.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/resampling/RegistrationQa.h"
#include "mvw/resampling/Transform.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::output {

namespace {

namespace fs = std::filesystem;
using resampling::Initialisation;
using resampling::Interpolation;
using resampling::RegistrationResult;

// Below this final MI (nats) a registration is reported as undetermined (a warning): the
// CT / PET-like pairs of the tests end near 1.0, the real T1 / CBF pair at 0.44, the nipy
// T1 / fMRI pair at 0.22.
constexpr double kWeakMutualInformation = 0.01;

// In the order the help and the messages list them.
const std::vector<std::pair<std::string, Interpolation>> kInterpolations = {
    {"auto", Interpolation::Automatic},
    {"linear", Interpolation::Linear},
    {"nearest", Interpolation::Nearest},
    {"cubic", Interpolation::Cubic}};
const std::vector<std::pair<std::string, Initialisation>> kInitialisations = {
    {"auto", Initialisation::Automatic},
    {"world", Initialisation::WorldCoordinates},
    {"centre", Initialisation::GeometricCentre},
    {"mass", Initialisation::CentreOfMass}};

template <typename T>
std::optional<T> lookUp(const std::vector<std::pair<std::string, T>>& table,
                        const std::string& name) {
  for (const auto& [k, v] : table)
    if (k == name) return v;
  return std::nullopt;
}

template <typename T>
std::vector<std::string> namesOf(const std::vector<std::pair<std::string, T>>& table) {
  std::vector<std::string> out;
  for (const auto& entry : table) out.push_back(entry.first);
  return out;
}

nlohmann::json rows(const glm::dmat4& m) {
  auto j = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) j.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return j;
}

nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
nlohmann::json vec(const glm::ivec3& v) { return {v.x, v.y, v.z}; }

std::string method(const RegistrationResult& r) { return r.affine ? "rigid then affine" : "rigid"; }

nlohmann::json levelsJson(const RegistrationResult& r) {
  auto levels = nlohmann::json::array();
  for (const auto& l : r.levels)
    levels.push_back({{"stage", l.stage},
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
  return levels;
}

// The resampled volume, and the interpolation that made it.
struct Resampled {
  Volume onGrid;
  Interpolation used = Interpolation::Linear;
};

// The QA picture, the transform and the resampled NIfTI, in the staging folder. `fixed` is
// taken by value and let go once its grid is known: the peak memory is the output's.
Resampled writeResampled(Volume fixed, const Volume& moving, const RegistrationResult& r,
                         Interpolation interpolation, const fs::path& staged) {
  resampling::ResampleOptions resampleOptions;
  resampleOptions.interpolation = interpolation;
  Resampled out;
  out.used = chosenInterpolation(moving, resampleOptions);
  // Before: the volumes as their headers place them in the world.
  io::writePng(registrationQaImage(fixed, moving, resampling::Transform(), r.transform),
               staged / "registration_qa.png");
  const resampling::Grid grid = resampling::gridOf(fixed);
  fixed = Volume();
  out.onGrid = resample(moving, grid, r.transform, resampleOptions);
  r.transform.writeItk(staged / "transform.tfm");
  io::writeVolume(out.onGrid, staged / "functional_on_anatomical.nii.gz");
  return out;
}

// The DICOM objects written, as the folder names them, and what the summary says of the series.
struct DicomResults {
  std::vector<std::string> names;
  std::string seriesNote;
};

DicomResults writeDicomResults(const fs::path& staged, const RegistrationIdentities& ids,
                               const RegistrationResult& r, const Volume& moving,
                               const Resampled& resampled, const std::string& fixedName) {
  DicomResults out;
  dicomout::SeriesInfo regSeries;
  regSeries.seriesNumber = 2001;
  regSeries.description = "mvw registration (" + std::string(r.affine ? "affine" : "rigid") + ")";
  dicomout::writeSpatialRegistration(staged / "registration.dcm", ids.fixed, ids.moving,
                                     r.transform.fixedFromMoving(), r.affine, regSeries,
                                     method(r) + ", Mattes mutual information (mvw register)");
  out.names.push_back("registration.dcm");
  dicomout::SeriesInfo series;
  series.seriesNumber = 2002;
  series.description =
      (moving.metadata().seriesDescription.empty() ? std::string("functional")
                                                   : moving.metadata().seriesDescription) +
      " on the anatomical grid";
  try {
    const int files = dicomout::writeVolumeSeries(
        staged / "functional_on_anatomical", resampled.onGrid, ids.moving, ids.fixed, series,
        "resampled onto the grid of " + fixedName + " by mvw register (" +
            interpolationName(resampled.used) + ")");
    out.names.push_back("functional_on_anatomical");
    out.seriesNote = "functional_on_anatomical/ (" + std::to_string(files) + " " +
                     ids.moving.modality + " images)";
  } catch (const InputError& e) {
    // A functional source that is not a DICOM PT, MR or CT series: the registration object
    // is written, the series is not, and the reader is told why.
    out.seriesNote = std::string("no DICOM series of the resampled volume: ") + e.what();
  }
  return out;
}

// What was written, on `out`; the warnings on `err`.
void sayWritten(const RegistrationRequest& request, const RegistrationInputs& inputs,
                const RegistrationResult& r, Interpolation used,
                const std::optional<RegistrationIdentities>& ids, const DicomResults& dicom,
                const std::vector<std::string>& warnings, std::ostream& out, std::ostream& err) {
  const glm::dvec3 degrees = registrationAngles(r) * (180.0 / std::numbers::pi);
  const glm::dvec3& t = r.parameters.translation;
  const fs::path& folder = request.output;
  out << (r.affine ? "registered (rigid + affine) " : "registered ") << inputs.movingName << " to "
      << inputs.fixedName << " in " << shortNumber(r.seconds) << " s, " << r.iterations
      << " iterations" << (r.converged ? "" : " (NOT converged)") << "\n"
      << "  rotation " << shortNumber(degrees.x) << ", " << shortNumber(degrees.y) << ", "
      << shortNumber(degrees.z) << " deg, translation " << shortNumber(t.x) << ", "
      << shortNumber(t.y) << ", " << shortNumber(t.z) << " mm\n"
      << "  wrote " << (folder / "transform.tfm").string() << ", "
      << (folder / "functional_on_anatomical.nii.gz").string() << " (" << interpolationName(used)
      << "), " << (folder / "registration_qa.png").string() << ", "
      << (folder / "registration.json").string() << "\n";
  if (ids)
    out << "  DICOM: " << (folder / "registration.dcm").string() << " (Spatial Registration, "
        << (r.affine ? "AFFINE" : "RIGID") << "), " << dicom.seriesNote << ", "
        << dicomout::identityNote(ids->fixed) << "\n";
  for (const std::string& w : warnings) err << "mvw register: warning: " << w << "\n";
}

}  // namespace

std::optional<Interpolation> parseInterpolation(const std::string& name) {
  return lookUp(kInterpolations, name);
}

std::string interpolationName(Interpolation interpolation) {
  for (const auto& [k, v] : kInterpolations)
    if (v == interpolation) return k;
  return "?";
}

std::vector<std::string> interpolationNames() { return namesOf(kInterpolations); }

std::optional<Initialisation> parseInitialisation(const std::string& name) {
  return lookUp(kInitialisations, name);
}

std::vector<std::string> initialisationNames() { return namesOf(kInitialisations); }

config::StudyConfig loadRegistrationStudy(const std::string& path, bool affine, std::ostream& err) {
  config::StudyConfig study = config::loadStudyConfig(path);
  if (!study.functional)
    throw InputError(path, "the study names no functional volume: nothing to register");
  const config::RegistrationConfig& r = study.registration;
  if (r.method == config::RegistrationMethod::File)
    err << "mvw register: note: the study places its functional volume by " << r.transform.string()
        << "; registering anew (rigid" << (affine ? " then affine" : "") << ")\n";
  return study;
}

void checkRegistrationFolder(const fs::path& output) {
  std::error_code ec;
  if (fs::exists(output, ec) && !fs::is_directory(output, ec))
    throw InputError(output, "exists and is not a folder");
  fs::path absolute = fs::absolute(output);
  if (!absolute.has_filename()) absolute = absolute.parent_path();  // "out/" names "out"
  if (!fs::is_directory(absolute.parent_path(), ec))
    throw InputError(absolute, "its parent folder does not exist");
}

RegistrationInputs readRegistrationInputs(const RegistrationRequest& request) {
  RegistrationInputs in;
  io::ReadOptions fixedRead, movingRead;
  fixedRead.suv = movingRead.suv = request.suv;
  if (request.study) {
    in.fixed = study::readAnatomical(request.study->anatomical, fixedRead, request.pacs);
    in.moving = study::readFunctional(*request.study, movingRead, request.pacs);
    in.fixedName = request.studyPath + " (anatomical)";
    in.movingName = request.studyPath + " (functional)";
    return in;
  }
  fixedRead.series = request.fixedSeries;
  movingRead.series = request.movingSeries;
  in.fixed = io::readVolume(request.fixed, fixedRead);
  in.moving = io::readVolume(request.moving, movingRead);
  in.fixedName = request.fixed;
  in.movingName = request.moving;
  return in;
}

RegistrationIdentities registrationIdentities(const Volume& fixed, const Volume& moving,
                                              const dicomout::GivenIdentity& given) {
  RegistrationIdentities ids;
  ids.fixed = dicomout::identityOf(fixed, given);
  dicomout::GivenIdentity movingGiven = given;
  if (moving.metadata().format != "DICOM") {
    if (movingGiven.patientId.empty()) movingGiven.patientId = ids.fixed.patientId;
    if (movingGiven.patientName.empty())
      movingGiven.patientName =
          ids.fixed.patientName.empty() ? ids.fixed.patientId : ids.fixed.patientName;
  }
  ids.moving = dicomout::identityOf(moving, movingGiven);
  return ids;
}

std::vector<std::string> registrationWarnings(const RegistrationResult& r) {
  // A final mutual information near 0: the volumes share next to no structure (one of them
  // nearly constant, or not the same anatomy), and any transform scores about the same. The
  // registration "converges" there all the same, so it is said, not left to the QA image.
  std::vector<std::string> warnings;
  if (!r.levels.empty() && r.levels.back().metricEnd < kWeakMutualInformation)
    warnings.push_back("the mutual information at the end is " +
                       shortNumber(r.levels.back().metricEnd, 2) + " (below " +
                       shortNumber(kWeakMutualInformation) +
                       "): the volumes share almost no structure, so the transform is not "
                       "determined by them; check registration_qa.png");
  return warnings;
}

glm::dvec3 registrationAngles(const RegistrationResult& r) {
  // The same matrix; the translation is unchanged.
  return resampling::rigidParameters(resampling::rigidMatrix(r.parameters, r.transform.centre()),
                                     r.transform.centre())
      .angles;
}

nlohmann::json registrationJson(const RegistrationResult& r, const RegistrationRecord& record) {
  nlohmann::json j;
  j["fixed"] = record.fixedName;
  j["moving"] = record.movingName;
  if (!record.studyPath.empty()) j["study"] = record.studyPath;
  j["method"] = method(r) + ", Mattes mutual information, quasi-Newton (BFGS) ascent";
  if (r.searchedRotations > 0)
    j["rotation_search"] = {{"range_deg", record.rotationSearchRangeDeg},
                            {"rotations_scored", r.searchedRotations},
                            {"best_angles_deg", vec(r.searchAngles * (180.0 / std::numbers::pi))}};
  j["runs"] = r.runs;
  j["runs_averaged"] = r.runsAveraged;
  j["sample_points_in"] =
      r.samplesInMoving ? "moving (its box is under half the fixed one's)" : "fixed";
  j["initialisation"] = toString(r.initialisation);
  j["initial_translation_mm"] = vec(r.initialTranslationMm);
  j["seed"] = record.seed;
  j["converged"] = r.converged;
  j["iterations"] = r.iterations;
  j["seconds"] = r.seconds;
  j["warnings"] = record.warnings;
  j["levels"] = levelsJson(r);
  // The parameters describe movingFromFixed (ITK's direction), about the centre; with affine
  // they are the rigid stage's, and the matrices below the final affine map. The angles are
  // ITK's decomposition of the same rotation (registrationAngles).
  const glm::dvec3 angles = registrationAngles(r);
  j["affine"] = r.affine;
  j["parameters"] = {
      {"convention", "moving = R (fixed - centre) + centre + translation, R = Rz Rx Ry"},
      {"angles_rad", vec(angles)},
      {"angles_deg", vec(angles * (180.0 / std::numbers::pi))},
      {"translation_mm", vec(r.parameters.translation)},
      {"centre_mm", vec(r.transform.centre())}};
  j["fixed_from_moving"] = rows(r.transform.fixedFromMoving());
  j["moving_from_fixed"] = rows(r.transform.movingFromFixed());
  j["interpolation"] = interpolationName(record.interpolation);
  j["outputs"] = record.outputs;
  return j;
}

RegistrationOutcome runRegistration(const RegistrationRequest& request, std::ostream& out,
                                    std::ostream& err) {
  // Everything is written into a staging folder first and moved into place at the end, so a
  // failure at any step leaves no partial result in the output folder.
  io::StagedFolder staging(request.output, {.purpose = "register"});
  RegistrationInputs inputs = readRegistrationInputs(request);
  const Volume moving = std::move(inputs.moving);
  // With DICOM output, the identities before the registration: a source without one is
  // refused now.
  std::optional<RegistrationIdentities> ids;
  if (request.dicom) ids = registrationIdentities(inputs.fixed, moving, *request.dicom);
  const RegistrationResult r = registerRigid(inputs.fixed, moving, request.options);
  const Resampled resampled =
      writeResampled(std::move(inputs.fixed), moving, r, request.interpolation, staging.path());
  DicomResults dicom;
  if (ids) dicom = writeDicomResults(staging.path(), *ids, r, moving, resampled, inputs.fixedName);

  RegistrationRecord record;
  record.fixedName = inputs.fixedName;
  record.movingName = inputs.movingName;
  record.studyPath = request.studyPath;
  record.rotationSearchRangeDeg = request.options.rotationSearchRangeDeg;
  record.seed = request.options.seed;
  record.interpolation = resampled.used;
  record.warnings = registrationWarnings(r);
  record.outputs = {"transform.tfm", "functional_on_anatomical.nii.gz", "registration_qa.png",
                    "registration.json"};
  record.outputs.insert(record.outputs.end(), dicom.names.begin(), dicom.names.end());
  {
    const fs::path file = staging.path() / "registration.json";
    std::ofstream json(file);
    json << registrationJson(r, record).dump(2) << "\n";
    if (!json) throw Error(file.string() + ": cannot write");
  }
  staging.commit(record.outputs);

  sayWritten(request, inputs, r, resampled.used, ids, dicom, record.warnings, out, err);
  RegistrationOutcome outcome;
  for (const std::string& name : dicom.names) outcome.dicomFiles.push_back(request.output / name);
  return outcome;
}

}  // namespace mvw::output
