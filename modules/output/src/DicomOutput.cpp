#include "mvw/output/DicomOutput.h"

#include "mvw/config/ServerList.h"
#include "mvw/core/Error.h"

namespace mvw::output {

namespace fs = std::filesystem;

void checkDicomDestination(const DicomOutputOptions& o, const fs::path& outDir) {
  if (!o.store.empty()) config::resolveServer(o.store);
  dicomout::checkUidRoot(o.uidRoot, "--uid-root");
  dicomout::setUidRoot(o.uidRoot);
  if (!o.dicom || o.force || outDir.empty()) return;
  std::error_code ec;
  if (fs::is_directory(outDir, ec) && !fs::is_empty(outDir, ec))
    throw InputError(outDir,
                     "exists and is not empty: DICOM objects go into a new or empty folder "
                     "(give --force to write into it)");
}

std::optional<StoredDicom> storeDicom(const DicomOutputOptions& o,
                                      const std::vector<fs::path>& files, const fs::path& where,
                                      const pacs::Options& connection) {
  if (o.store.empty()) return std::nullopt;
  const pacs::Server server = config::resolveServer(o.store);
  pacs::Options options = connection;
  options.callingAet = o.storeOptions.callingAet;
  options.insecure = o.storeOptions.insecure;
  options.progress = false;
  try {
    return StoredDicom{pacs::store(server, files, options), server.text};
  } catch (const ServiceError& e) {
    throw ServiceError(std::string(e.what()) + " (the DICOM objects stay written in " +
                       where.string() + "; send them with mvw pacs store)");
  }
}

}  // namespace mvw::output
