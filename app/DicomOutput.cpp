#include "DicomOutput.h"

#include <ostream>

#include "CliChecks.h"
#include "PacsCommand.h"

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
  cmd.add_option("--store", o.store,
                 "Once every DICOM object is written, send them to this PACS: "
                 "http(s)://host:port/PATH (STOW-RS) or dicom://AET@host:port (C-STORE), as "
                 "`mvw pacs store`, or a server's name saved in servers.json; exit 3 when the "
                 "server fails (the files stay written)")
      ->check(nonEmpty());
  addServerOptions(cmd, o.storeOptions);
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
    if (!o.store.empty())
      throw CLI::ValidationError("--store",
                                 "sends the DICOM objects the command writes: it needs "
                                 "--dicom (stats: --seg FILE)");
  }
  const pacs::Options defaults;
  if (o.store.empty() && (o.storeOptions.callingAet != defaults.callingAet ||
                          o.storeOptions.insecure != defaults.insecure))
    throw CLI::ValidationError(o.storeOptions.insecure ? "--insecure" : "--calling-aet",
                               "goes with --store SERVER");
  output::checkDicomDestination(o, outDir);
}

void storeDicom(const DicomOutputOptions& o, const pacs::Options& timeouts,
                const std::vector<fs::path>& files, const fs::path& where, std::ostream& out) {
  if (const auto stored = output::storeDicom(o, files, where, timeouts))
    out << transferSummary("stored", stored->transfer) << " to " << stored->server << "\n";
}

}  // namespace mvw::app
