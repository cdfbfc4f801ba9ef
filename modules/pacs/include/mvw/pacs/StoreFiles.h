#pragma once
// What `mvw pacs store SERVER FILE...` sends: a folder is what a command wrote (`mvw render
// --dicom` puts its PNGs and render.json beside the DICOM objects), so only its DICOM files go
// and the rest is said to be skipped; a file named on its own is meant, so one that is not
// DICOM is refused.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace mvw::pacs {

struct StoreFiles {
  std::vector<std::filesystem::path> files;    // to send, in the order given (folders: by path)
  std::vector<std::filesystem::path> skipped;  // under a folder given, not DICOM
  std::uint64_t bytes = 0;                     // of `files`
};

// Each file named, and every DICOM file (one with a SOP Instance UID) under each folder named.
// Throws InputError naming a file named that cannot be read or is not DICOM, or naming the
// first input when nothing is left to send ("holds no DICOM files to store").
StoreFiles storeFiles(const std::vector<std::filesystem::path>& inputs);

}  // namespace mvw::pacs
