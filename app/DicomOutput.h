#pragma once
// The options that make render, register and stats write DICOM objects (--dicom, --seg) and
// send them to a PACS (--store SERVER), what they check before any work (the identity for a
// source that is not DICOM, the UID root, an output folder that is not empty, the server's
// syntax), and the store itself once every object is written.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::app {

struct DicomOutputOptions {
  bool dicom = false;  // render, register: --dicom (stats: --seg FILE)
  bool force = false;  // write into an output folder that is not empty
  std::string patientId, patientName, uidRoot;
  std::string store;           // --store SERVER: empty, nothing is sent
  pacs::Options storeOptions;  // its --calling-aet and --insecure (time-outs: storeDicom's)
  dicomout::GivenIdentity given() const { return {patientId, patientName}; }
};

// --patient-id, --patient-name, --uid-root, --store SERVER (with `mvw pacs`'s --calling-aet and
// --insecure); with withFolder, --dicom and --force.
void addDicomOptions(CLI::App& cmd, DicomOutputOptions& o, bool withFolder);

// Before any work: the DICOM options (--store among them) go with a DICOM output (writing:
// --dicom or --seg), the UID root is valid (and taken), --store names a server mvw can reach
// (its syntax: pacs::parseServer), and with --dicom an output folder that exists is empty
// unless --force. Throws CLI::ValidationError or InputError naming the folder or the server.
void checkDicomOutput(const DicomOutputOptions& o, bool writing,
                      const std::filesystem::path& outDir);

// With --store: `files` (every DICOM object the command wrote, all of them written) sent to the
// server by pacs::store, and one line said on `out`, with the time-outs of `timeouts` (the
// command line's --connect-timeout and --read-timeout, those the study's PACS series are read
// with). A server that refuses or cannot be reached is a ServiceError naming it, which adds
// that the objects stay written in `where`.
void storeDicom(const DicomOutputOptions& o, const pacs::Options& timeouts,
                const std::vector<std::filesystem::path>& files, const std::filesystem::path& where,
                std::ostream& out);

}  // namespace mvw::app
