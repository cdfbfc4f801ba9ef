#pragma once
// The DICOM objects render, register and stats write (--dicom, --seg) and their sending to a
// PACS (--store SERVER): what is checked before any work, and the store once every object is
// written. app/ registers the options and keeps the checks of the command line itself (which
// options go together); these are the rest.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::output {

struct DicomOutputOptions {
  bool dicom = false;  // render, register: --dicom (stats: --seg FILE)
  bool force = false;  // write into an output folder that is not empty
  std::string patientId, patientName, uidRoot;
  std::string store;           // --store SERVER: empty, nothing is sent
  pacs::Options storeOptions;  // its --calling-aet and --insecure (time-outs: storeDicom's)
  dicomout::GivenIdentity given() const { return {patientId, patientName}; }
};

// Before any work: --store names a server mvw can reach (a URL, AET@host:port or a name saved
// in servers.json: config::resolveServer), the UID root is valid (and taken for every new UID:
// dicomout::setUidRoot), and with `dicom` an output folder that exists is empty unless `force`.
// Throws InputError naming the server (or listing the saved names), the root or the folder.
void checkDicomDestination(const DicomOutputOptions& o, const std::filesystem::path& outDir);

// What a store sent, and to which server (the resolved server's text).
struct StoredDicom {
  pacs::Transfer transfer;
  std::string server;
};

// With a --store server (resolved by config::resolveServer): `files` (every DICOM object the
// command wrote, all of them written) sent by pacs::store over `connection` (its time-outs: the
// command line's --connect-timeout and --read-timeout, those the study's PACS series are read
// with; the AE title and HTTPS check are the options'). Without one, nothing. A server that refuses
// or cannot be reached is a ServiceError naming it, which adds that the objects stay written in
// `where`.
std::optional<StoredDicom> storeDicom(const DicomOutputOptions& o,
                                      const std::vector<std::filesystem::path>& files,
                                      const std::filesystem::path& where,
                                      const pacs::Options& connection);

}  // namespace mvw::output
