#pragma once
// `mvw register` as a function: a functional volume registered to an anatomical one (two files,
// or a study config's pair), resampled onto its grid, and the results in a folder: the ITK
// transform, the resampled NIfTI, the QA picture, registration.json, and with a DICOM identity
// the Spatial Registration and the resampled series. Everything goes into a staging folder and
// is moved into place at the end, so a failure leaves no partial result.
//
// It lives here rather than in study because it writes DICOM objects (dicomout, which study
// does not reach), and rather than in resampling because it reads a study config's volumes and
// writes files: output is the module that turns a loaded study into a folder of results.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/resampling/Resample.h"
#include "mvw/resampling/RigidRegistration.h"

namespace mvw::output {

// The names `mvw register` gives its resampling choices on the command line and in
// registration.json: auto, linear, nearest, cubic.
std::optional<resampling::Interpolation> parseInterpolation(const std::string& name);
std::string interpolationName(resampling::Interpolation interpolation);
// --init's names: auto, world, centre, mass.
std::optional<resampling::Initialisation> parseInitialisation(const std::string& name);
// The names above, in that order: what the command line accepts and what messages list.
std::vector<std::string> interpolationNames();
std::vector<std::string> initialisationNames();

// What to register and where the results go.
struct RegistrationRequest {
  // A study config (its path as given, and the loaded config): its anatomical (fixed) and
  // functional (moving) volumes, read as every command reads the study. Without one, the files
  // `fixed` and `moving`, with their DICOM series choices.
  std::string studyPath;
  std::optional<config::StudyConfig> study;
  pacs::Options pacs;  // the study's reads: the command line's --cache and time-outs
  std::string fixed, moving;
  std::string fixedSeries, movingSeries;
  bool suv = true;               // PET values in SUVbw (else Bq/ml)
  std::filesystem::path output;  // the results' folder, as given (messages name it so)
  resampling::RegistrationOptions options;
  resampling::Interpolation interpolation = resampling::Interpolation::Automatic;
  // With a value, the results as DICOM too (registration.dcm and the resampled series),
  // identified by the sources, and by this where a source has no identity.
  std::optional<dicomout::GivenIdentity> dicom;
};

// A study config to register: loaded, and refused (InputError) when it names no functional
// volume. A study that places its functional volume by a transform file is registered anew,
// as `err` is told (`affine`: the command line asks for the affine stage).
config::StudyConfig loadRegistrationStudy(const std::string& path, bool affine, std::ostream& err);

// Before any heavy work: the output folder is made if missing, its parent is not. Throws
// InputError when it is a file or its parent folder does not exist.
void checkRegistrationFolder(const std::filesystem::path& output);

// The two volumes, and their names as the outputs give them ("STUDY (anatomical)" or the
// file's path).
struct RegistrationInputs {
  Volume fixed, moving;
  std::string fixedName, movingName;
};
RegistrationInputs readRegistrationInputs(const RegistrationRequest& request);

// The DICOM identities of both volumes, known before the registration so that a source
// without one is refused first. A moving volume that is not DICOM joins the fixed one's
// patient (ID, and name or else ID) unless `given` names them.
struct RegistrationIdentities {
  dicomout::DicomIdentity fixed, moving;
};
RegistrationIdentities registrationIdentities(const Volume& fixed, const Volume& moving,
                                              const dicomout::GivenIdentity& given);

// What registration.json says besides the registration's result.
struct RegistrationRecord {
  std::string fixedName, movingName;
  std::string studyPath;  // "" : no study config
  double rotationSearchRangeDeg = 0.0;
  std::uint64_t seed = 0;
  resampling::Interpolation interpolation = resampling::Interpolation::Linear;  // the one used
  std::vector<std::string> warnings;
  std::vector<std::string> outputs;  // the files written, as the folder names them
};

// What the registration's result warns of: a final mutual information near 0 (the volumes
// share next to no structure, so the transform is not determined by them).
std::vector<std::string> registrationWarnings(const resampling::RegistrationResult& result);

// The rotation of the result (radians about x, y, z) in ITK's own decomposition (x within
// +-90 degrees): the optimiser's angles may be an equivalent triple such as (-180, -180, 180)
// degrees for no rotation at all (after a rotation search), which reads as a large rotation.
glm::dvec3 registrationAngles(const resampling::RegistrationResult& result);

// registration.json.
nlohmann::json registrationJson(const resampling::RegistrationResult& result,
                                const RegistrationRecord& record);

// The DICOM objects a run wrote (paths in the output folder, in the order written).
struct RegistrationOutcome {
  std::vector<std::filesystem::path> dicomFiles;
};

// The whole run: reads the inputs, registers, writes and moves every result into place, then
// says what was written on `out` (and the warnings on `err`). Throws InputError for inputs or
// an identity that cannot be used; leaves no partial output.
RegistrationOutcome runRegistration(const RegistrationRequest& request, std::ostream& out,
                                    std::ostream& err);

}  // namespace mvw::output
