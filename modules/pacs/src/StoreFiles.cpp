#include "mvw/pacs/StoreFiles.h"

#include <algorithm>

#include "Internal.h"
#include "mvw/core/Error.h"

namespace mvw::pacs {

namespace fs = std::filesystem;

StoreFiles storeFiles(const std::vector<fs::path>& inputs) {
  StoreFiles chosen;
  for (const fs::path& p : inputs) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> inDir;
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file()) inDir.push_back(e.path());
      std::sort(inDir.begin(), inDir.end());
      for (const fs::path& f : inDir) {
        if (detail::readUids(f)) {
          chosen.files.push_back(f);
          chosen.bytes += fs::file_size(f);
        } else {
          chosen.skipped.push_back(f);
        }
      }
    } else {
      requireReadable(p);
      if (!detail::readUids(p)) throw InputError(p, "is not a DICOM file with a SOP Instance UID");
      chosen.files.push_back(p);
      chosen.bytes += fs::file_size(p);
    }
  }
  if (chosen.files.empty())
    throw InputError(
        inputs.empty() ? fs::path("FILE") : inputs.front(),
        chosen.skipped.empty() ? "holds no files to store" : "holds no DICOM files to store");
  return chosen;
}

}  // namespace mvw::pacs
