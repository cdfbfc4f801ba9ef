#include "mvw/batch/BatchInputs.h"

#include <filesystem>
#include <vector>

#include "mvw/config/StudyConfig.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

const char* const kRole = "an input of a batch study";

}  // namespace

std::string pacsInputKey(const std::string& server, const std::string& study,
                         const std::string& series) {
  return "pacs " + server + " study " + study + " series " + series;
}

std::map<std::string, std::string> batchInputChecksums(const BatchStudy& study,
                                                       BatchHashCache* cache) {
  BatchHashCache none;
  BatchHashCache& hashes = cache ? *cache : none;
  std::map<std::string, std::string> sums;
  sums[study.study.string()] = hashes.fileSha256(study.study, kRole);
  std::vector<fs::path> paths;
  if (study.study.extension() == ".json") {
    const config::StudyConfig config = config::loadStudyConfig(study.study);
    // A PACS series is what the config names, not bytes here: the identity itself is hashed, so
    // the study reruns when the config names another server, study or series (its bytes
    // change anyway), never because the cache was filled or emptied between runs.
    auto add = [&](const config::VolumeSource& source) {
      if (source.pacs.empty()) {
        paths.push_back(source.path);
        return;
      }
      const std::string key = pacsInputKey(source.pacs, source.study, source.series);
      process::Sha256 sha;
      sha.add(key.data(), key.size());
      sums[key] = sha.hex();
    };
    add(config.anatomical);
    if (config.functional) add(*config.functional);
    if (config.segmentation) add(*config.segmentation);
    if (!config.registration.transform.empty()) paths.push_back(config.registration.transform);
  }
  // An option naming a file (a label table, a transform) is an input too.
  for (const auto& [name, value] : study.options) {
    if (value.empty() || value.find(' ') != std::string::npos) continue;
    fs::path p = value;
    std::error_code ec;
    if (fs::is_regular_file(p, ec) || fs::is_directory(p, ec)) paths.push_back(fs::absolute(p));
  }
  for (const auto& p : paths) {
    const fs::path abs = fs::absolute(p).lexically_normal();
    if (!sums.count(abs.string())) sums[abs.string()] = hashes.pathSha256(abs, kRole);
  }
  return sums;
}

}  // namespace mvw::batch
