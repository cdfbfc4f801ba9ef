#pragma once
// The exact half of golden comparison: SHA-256 of an image's decoded pixels, and the manifest
// that records them with the GL renderer they were made on (a suite's "checksums" file). On
// that renderer a render must hash to its golden's checksum; on any other, only the tolerances
// apply (GL implementations differ in the last bit of texture filtering).
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace mvw::validate {

// Lower-case hex SHA-256 of the pixel bytes, row by row (no padding), then of the width,
// height and channel count as text, so a transposed or re-channelled image differs. The PNG
// encoding (compression level, metadata) does not enter.
std::string pixelSha256(const cv::Mat& image);

struct ChecksumManifest {
  std::filesystem::path file;
  std::string glRenderer, glVersion;          // what the checksums were made on
  std::map<std::string, std::string> images;  // reference path relative to file's folder -> hex

  // The key a reference image has in `images`.
  std::string keyOf(const std::filesystem::path& reference) const;
  // True when a render made on this renderer must match the checksums exactly.
  bool exactOn(const std::string& renderer, const std::string& version) const {
    return !glRenderer.empty() && renderer == glRenderer && version == glVersion;
  }
};

// Throws InputError naming the file when it is missing, not JSON or not a manifest.
ChecksumManifest loadChecksumManifest(const std::filesystem::path& file);
// Written atomically, keys sorted, one image per line.
void writeChecksumManifest(const ChecksumManifest& manifest);

}  // namespace mvw::validate
