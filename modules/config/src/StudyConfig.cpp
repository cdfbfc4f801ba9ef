#include "mvw/config/StudyConfig.h"

#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"

namespace mvw::config {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::map<std::string, FunctionalKind> kKinds = {
    {"pet", FunctionalKind::Pet},     {"spect", FunctionalKind::Spect},
    {"fmri", FunctionalKind::Fmri},   {"perfusion", FunctionalKind::Perfusion},
    {"dose", FunctionalKind::Dose},   {"labels", FunctionalKind::Labels},
    {"other", FunctionalKind::Other}};

void rejectUnknownKeys(const fs::path& file, const json& object, const std::string& where,
                       const std::set<std::string>& known) {
  for (const auto& [key, value] : object.items()) {
    if (known.count(key)) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw InputError(file, "unknown key '" + where + key + "' (known here: " + list + ")");
  }
}

std::string stringField(const fs::path& file, const json& object, const std::string& where,
                        const std::string& key, bool required) {
  if (!object.contains(key)) {
    if (required) throw InputError(file, "missing key '" + where + key + "'");
    return {};
  }
  if (!object[key].is_string()) throw InputError(file, "'" + where + key + "' must be a string");
  return object[key].get<std::string>();
}

VolumeSource volumeSource(const fs::path& file, const json& j, const std::string& name,
                          const std::set<std::string>& extraKeys = {}) {
  if (!j.is_object()) throw InputError(file, "'" + name + "' must be an object with a \"path\"");
  std::set<std::string> known = {"path", "series"};
  known.insert(extraKeys.begin(), extraKeys.end());
  rejectUnknownKeys(file, j, name + ".", known);
  VolumeSource s;
  const std::string p = stringField(file, j, name + ".", "path", true);
  if (p.empty()) throw InputError(file, "'" + name + ".path' is empty");
  s.path = fs::path(p).is_absolute() ? fs::path(p) : file.parent_path() / p;
  s.path = s.path.lexically_normal();
  std::error_code ec;
  if (!fs::exists(s.path, ec))
    throw InputError(file, "'" + name + ".path' names " + s.path.string() + ", which does not exist");
  s.series = stringField(file, j, name + ".", "series", false);
  return s;
}

}  // namespace

StudyConfig loadStudyConfig(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open the study config");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(file, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(file, "a study config must be a JSON object");
  rejectUnknownKeys(file, j, "", {"name", "anatomical", "functional"});
  StudyConfig config;
  config.file = file;
  config.name = stringField(file, j, "", "name", false);
  if (!j.contains("anatomical")) throw InputError(file, "missing key 'anatomical'");
  config.anatomical = volumeSource(file, j["anatomical"], "anatomical");
  if (j.contains("functional")) {
    config.functional = volumeSource(file, j["functional"], "functional", {"kind"});
    const std::string kind = stringField(file, j["functional"], "functional.", "kind", false);
    if (!kind.empty()) {
      auto it = kKinds.find(kind);
      if (it == kKinds.end())
        throw InputError(file, "'functional.kind' is '" + kind +
                                   "'; use pet, spect, fmri, perfusion, dose, labels or other");
      config.functionalKind = it->second;
    }
  }
  return config;
}

std::string toString(FunctionalKind kind) {
  for (const auto& [name, k] : kKinds)
    if (k == kind) return name;
  return "other";
}

}  // namespace mvw::config
