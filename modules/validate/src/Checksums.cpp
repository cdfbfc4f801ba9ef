#include "mvw/validate/Checksums.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/process/Sha256.h"

namespace mvw::validate {

namespace fs = std::filesystem;
using nlohmann::json;

std::string pixelSha256(const cv::Mat& image) {
  process::Sha256 sha;
  const std::size_t rowBytes = image.cols * image.elemSize();
  for (int y = 0; y < image.rows; ++y) sha.add(image.ptr(y), rowBytes);
  const std::string shape = std::to_string(image.cols) + "x" + std::to_string(image.rows) + "x" +
                            std::to_string(image.channels());
  sha.add(shape.data(), shape.size());
  return sha.hex();
}

std::string ChecksumManifest::keyOf(const fs::path& reference) const {
  return fs::absolute(reference)
      .lexically_normal()
      .lexically_relative(fs::absolute(file).parent_path().lexically_normal())
      .generic_string();
}

ChecksumManifest loadChecksumManifest(const fs::path& file) {
  ChecksumManifest m;
  m.file = file;
  if (fs::is_directory(file))
    throw InputError(file, "is a folder, not a checksum manifest (.json)");
  std::ifstream in(file);
  if (!in) throw InputError(file, "no such checksum manifest (mvw validate --update writes it)");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(file, std::string("not valid JSON: ") + e.what());
  }
  const auto text = [&](const char* key) {
    if (!root.is_object() || !root.contains(key) || !root[key].is_string())
      throw InputError(file, std::string("\"") + key + "\" (a string) is required");
    return root[key].get<std::string>();
  };
  m.glRenderer = text("gl_renderer");
  m.glVersion = text("gl_version");
  if (!root.contains("images") || !root["images"].is_object())
    throw InputError(file, "\"images\" (reference path -> SHA-256) is required");
  for (const auto& [key, value] : root["images"].items()) {
    if (!value.is_string() || value.get<std::string>().size() != 64)
      throw InputError(file, "images \"" + key + "\": not a SHA-256 (64 hex digits)");
    m.images[key] = value.get<std::string>();
  }
  return m;
}

void writeChecksumManifest(const ChecksumManifest& m) {
  json root;
  root["description"] =
      "SHA-256 of the decoded pixels of each golden (mvw validate): renders on this GL renderer "
      "must match them exactly; elsewhere only the suite's tolerances apply. Written by "
      "mvw validate --update.";
  root["gl_renderer"] = m.glRenderer;
  root["gl_version"] = m.glVersion;
  root["images"] = json::object();
  for (const auto& [key, sha] : m.images) root["images"][key] = sha;
  io::writeTextAtomically(m.file, root.dump(2) + "\n");
}

}  // namespace mvw::validate
