#include "DicomOutput.h"

#include "CliChecks.h"
#include "mvw/core/Error.h"

namespace mvw::app {

namespace fs = std::filesystem;

void addDicomOptions(CLI::App& cmd, DicomOutputOptions& o, bool withFolder) {
  if (withFolder) {
    cmd.add_flag("--dicom", o.dicom,
                 "Also write the results as DICOM objects in the patient's study (see the user "
                 "guide's DICOM output page)");
    cmd.add_flag("--force", o.force,
                 "With --dicom: write into an output folder that exists and is not empty");
  }
  cmd.add_option("--patient-id", o.patientId,
                 "DICOM output: the Patient ID (needed where the source is not DICOM or has none)")
      ->check(nonEmpty());
  cmd.add_option("--patient-name", o.patientName,
                 "DICOM output: the patient's name, DICOM style (Family^Given)")
      ->check(nonEmpty());
  cmd.add_option("--uid-root", o.uidRoot,
                 "DICOM output: an organisation's UID root for the new UIDs (default 2.25, a UUID)")
      ->check(nonEmpty());
}

void checkDicomOutput(const DicomOutputOptions& o, bool writing, const fs::path& outDir) {
  if (!writing) {
    const char* given = !o.patientId.empty()     ? "--patient-id"
                        : !o.patientName.empty() ? "--patient-name"
                        : !o.uidRoot.empty()     ? "--uid-root"
                        : o.force                ? "--force"
                                                 : nullptr;
    if (given)
      throw CLI::ValidationError(given, "goes with a DICOM output (--dicom, or --seg for stats)");
  }
  dicomout::checkUidRoot(o.uidRoot, "--uid-root");
  dicomout::setUidRoot(o.uidRoot);
  if (!o.dicom || o.force || outDir.empty()) return;
  std::error_code ec;
  if (fs::is_directory(outDir, ec) && !fs::is_empty(outDir, ec))
    throw InputError(outDir,
                     "exists and is not empty: DICOM objects go into a new or empty folder "
                     "(give --force to write into it)");
}

std::string identityNote(const dicomout::DicomIdentity& id) {
  if (id.fromDicom)
    return "in the study " + id.studyInstanceUid + " of patient " + id.patientId +
           " (from the DICOM source)";
  return "in a NEW study " + id.studyInstanceUid + " for patient " + id.patientId + " (" +
         id.patientName + "): the source is not DICOM";
}

}  // namespace mvw::app
