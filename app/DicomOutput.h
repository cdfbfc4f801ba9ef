#pragma once
// The options that make render, register and stats write DICOM objects (--dicom, --seg), and
// what they check before any work: the identity for a source that is not DICOM, the UID root,
// an output folder that is not empty.
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "mvw/dicomout/DicomIdentity.h"

namespace mvw::app {

struct DicomOutputOptions {
  bool dicom = false;  // render, register: --dicom (stats: --seg FILE)
  bool force = false;  // write into an output folder that is not empty
  std::string patientId, patientName, uidRoot;
  dicomout::GivenIdentity given() const { return {patientId, patientName}; }
};

// --patient-id, --patient-name, --uid-root; with withFolder, --dicom and --force.
void addDicomOptions(CLI::App& cmd, DicomOutputOptions& o, bool withFolder);

// Before any work: the DICOM options go with a DICOM output (writing: --dicom or --seg), the
// UID root is valid (and taken), and with --dicom an output folder that exists is empty unless
// --force. Throws CLI::ValidationError or InputError naming the folder.
void checkDicomOutput(const DicomOutputOptions& o, bool writing,
                      const std::filesystem::path& outDir);

// The line that tells the reader whose study the objects went into.
std::string identityNote(const dicomout::DicomIdentity& id);

}  // namespace mvw::app
