#include "mvw/batch/BatchManifest.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"

namespace mvw::batch {

namespace fs = std::filesystem;

const std::vector<std::string>& batchTasks() {
  static const std::vector<std::string> tasks{"render", "stats", "register"};
  return tasks;
}

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// One CSV line (RFC 4180 quoting, no line breaks inside quotes). False when a quote is open.
bool splitCsv(const std::string& line, std::vector<std::string>& fields) {
  fields.clear();
  std::string field;
  bool quoted = false, wasQuoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"' && trim(field).empty()) {
      quoted = wasQuoted = true;
      field.clear();
    } else if (c == ',') {
      fields.push_back(wasQuoted ? field : trim(field));
      field.clear();
      wasQuoted = false;
    } else {
      field += c;
    }
  }
  if (quoted) return false;
  fields.push_back(wasQuoted ? field : trim(field));
  return true;
}

// An id is a folder name on every file system the output may land on.
std::string whyBadId(const std::string& id) {
  if (id.empty()) return "the id is empty";
  if (id.size() > 100) return "the id '" + id.substr(0, 20) + "...' is longer than 100 characters";
  if (id[0] == '.' || id[0] == '-')
    return "the id '" + id + "' starts with '" + id.substr(0, 1) + "' (ids are folder names)";
  for (const char c : id)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'))
      return "the id '" + id + "' has '" + std::string(1, c) +
             "': ids are folder names of letters, digits, '-', '_' and '.'";
  return "";
}

std::string whyBadOptionName(const std::string& name) {
  if (name.empty()) return "an option column has no name";
  for (const char c : name)
    if (!(std::islower(static_cast<unsigned char>(c)) ||
          std::isdigit(static_cast<unsigned char>(c)) || c == '-'))
      return "the option column '" + name +
             "' is not an option name (lower-case letters, digits and '-', without the leading "
             "dashes)";
  if (name[0] == '-')
    return "the option column '" + name + "' starts with '-': leave the dashes out";
  static const std::vector<std::string> reserved{"o", "output", "json", "fixed", "moving"};
  if (std::find(reserved.begin(), reserved.end(), name) != reserved.end())
    return "the option column '" + name + "' is set by mvw batch itself";
  return "";
}

// Edits turning one name into the other (Levenshtein), for "did you mean".
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Why the option `name` = `value` (as addOption stored it: "" for true) cannot go to `task`'s
// command, "" when it can. The message is the one a user reads for the whole manifest, so it
// names the option and the command, and what to write instead.
std::string whyNotTaskOption(const TaskOptions& known, const std::string& task,
                             const std::string& name, const std::string& value) {
  const auto options = known.find(task);
  if (options == known.end()) return "";
  const std::string command = "mvw " + task;
  const auto it = options->second.find(name);
  if (it == options->second.end()) {
    std::string closest;
    std::size_t best = 3;  // at most 2 edits away: a typo, not another option
    for (const auto& [candidate, how] : options->second)
      if (const std::size_t d = editDistance(name, candidate); d < best) {
        best = d;
        closest = candidate;
      }
    std::string why = "'" + name + "' is not an option of " + command;
    if (name == "options")
      why +=
          " (a CSV manifest has one column per option, named as the option without its "
          "dashes: size, view, ...; \"options\" is the JSON manifest's object of them)";
    else if (!closest.empty())
      why += " (did you mean '" + closest + "'?)";
    else
      why += " (" + command + " --help lists them)";
    return why;
  }
  const TaskOption& how = it->second;
  if (how.flag && !value.empty())
    return "'" + name + "' is a flag of " + command + ": true, false or empty, not '" + value + "'";
  if (!how.flag && value.empty())
    return "'" + name + "' of " + command + " takes a value, not true";
  std::istringstream words(value);
  int count = 0;
  for (std::string w; words >> w; ++count)
    if (w.rfind("--", 0) == 0)
      return "the value of '" + name + "' holds '" + w +
             "': each option is a column of its own (or a key of \"options\" in JSON), its "
             "cell the value";
  if (count > how.maxValues)
    return "'" + name + "' of " + command + " takes " +
           (how.maxValues == 1 ? std::string("one value")
                               : "at most " + std::to_string(how.maxValues) + " values") +
           ", not " + std::to_string(count) + " ('" + value +
           "': a value is split at its spaces, quoted or not)";
  return "";
}

void addStudy(BatchManifest& manifest, std::map<std::string, int>& ids, BatchStudy study,
              const std::string& where, const TaskOptions& known) {
  const fs::path& file = manifest.file;
  if (const std::string why = whyBadId(study.id); !why.empty())
    throw InputError(file, where + ": " + why);
  if (const auto it = ids.find(study.id); it != ids.end())
    throw InputError(file, where + ": the id '" + study.id + "' is already used on line " +
                               std::to_string(it->second));
  const auto& tasks = batchTasks();
  if (std::find(tasks.begin(), tasks.end(), study.task) == tasks.end())
    throw InputError(file,
                     where + ": unknown task '" + study.task + "' (render, stats or register)");
  if (study.study.empty()) throw InputError(file, where + ": the study column is empty");
  fs::path config = study.study;
  if (config.is_relative()) config = file.parent_path() / config;
  config = config.lexically_normal();
  if (const std::string why = whyUnreadable(config); !why.empty())
    throw InputError(file, where + ": the study config " + config.string() + ": " + why);
  study.study = fs::absolute(config);
  for (const auto& [name, value] : study.options) {
    if (const std::string why = whyBadOptionName(name); !why.empty())
      throw InputError(file, where + ": " + why);
    if (const std::string why = whyNotTaskOption(known, study.task, name, value); !why.empty())
      throw InputError(file, where + ": " + why);
  }
  // An option naming a file relative to the manifest (a label table) is made absolute, as the
  // study column is: the children run elsewhere.
  for (auto& [name, value] : study.options) {
    if (value.empty() || value.find(' ') != std::string::npos || fs::path(value).is_absolute())
      continue;
    std::error_code ec;
    const fs::path p = (file.parent_path() / value).lexically_normal();
    if (fs::exists(p, ec)) value = fs::absolute(p).string();
  }
  ids.emplace(study.id, study.lineNumber);
  manifest.studies.push_back(std::move(study));
}

// "true" is a flag, "false" and "" leave the option out.
void addOption(BatchStudy& study, const std::string& name, const std::string& value) {
  if (value.empty() || value == "false") return;
  study.options.emplace_back(name, value == "true" ? "" : value);
}

BatchManifest loadCsv(const fs::path& file, std::istream& in, const TaskOptions& known) {
  BatchManifest manifest{file, {}};
  std::map<std::string, int> ids;
  std::vector<std::string> header, fields;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const std::string where = "line " + std::to_string(number);
    if (!splitCsv(line, fields)) throw InputError(file, where + ": a quote is not closed");
    if (header.empty()) {
      header = fields;
      if (header.size() < 3 || header[0] != "id" || header[1] != "study" || header[2] != "task")
        throw InputError(
            file, where + ": the header must start with id,study,task (it is '" + line + "')");
      std::map<std::string, int> seen;
      for (std::size_t i = 3; i < header.size(); ++i) {
        if (const std::string why = whyBadOptionName(header[i]); !why.empty())
          throw InputError(file, where + ": " + why);
        if (!seen.emplace(header[i], 0).second)
          throw InputError(file, where + ": the column '" + header[i] + "' is there twice");
      }
      continue;
    }
    if (fields.size() != header.size())
      throw InputError(file, where + ": " + std::to_string(fields.size()) +
                                 " fields, the header has " + std::to_string(header.size()));
    BatchStudy study;
    study.id = fields[0];
    study.studyText = fields[1];
    study.study = fields[1];
    study.task = fields[2];
    for (std::size_t i = 3; i < header.size(); ++i) addOption(study, header[i], fields[i]);
    study.line = line;
    study.lineNumber = number;
    addStudy(manifest, ids, std::move(study), where, known);
  }
  if (header.empty()) throw InputError(file, "is empty: no header id,study,task");
  return manifest;
}

BatchManifest loadJson(const fs::path& file, std::istream& in, const TaskOptions& known) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, std::string("is not valid JSON: ") + e.what());
  }
  const nlohmann::json* list = &j;
  if (j.is_object()) {
    for (const auto& [key, value] : j.items())
      if (key != "studies") throw InputError(file, "unknown key '" + key + "' (only \"studies\")");
    if (!j.contains("studies")) throw InputError(file, "has no \"studies\" list");
    list = &j["studies"];
  }
  if (!list->is_array()) throw InputError(file, "\"studies\" must be a list of objects");
  BatchManifest manifest{file, {}};
  std::map<std::string, int> ids;
  int index = 0;
  for (const auto& entry : *list) {
    ++index;
    const std::string where = "study " + std::to_string(index);
    if (!entry.is_object()) throw InputError(file, where + ": not an object");
    BatchStudy study;
    for (const auto& [key, value] : entry.items()) {
      if (key == "id" || key == "study" || key == "task") {
        if (!value.is_string())
          throw InputError(file, where + ": \"" + key + "\" must be a string");
        (key == "id" ? study.id : key == "task" ? study.task : study.studyText) = value;
      } else if (key == "options") {
        if (!value.is_object())
          throw InputError(file, where +
                                     ": \"options\" must be an object of options named without "
                                     "their dashes: {\"size\": 256, \"mode\": \"mip\"}");
        for (const auto& [name, v] : value.items()) {
          std::string text;
          if (v.is_string())
            text = v.get<std::string>();
          else if (v.is_boolean())
            text = v.get<bool>() ? "true" : "false";
          else if (v.is_number())
            text = v.dump();
          else if (v.is_array()) {
            for (const auto& x : v) {
              if (!x.is_number() && !x.is_string())
                throw InputError(file,
                                 where + ": option '" + name + "': a list of numbers or strings");
              text += (text.empty() ? "" : " ") + (x.is_string() ? x.get<std::string>() : x.dump());
            }
          } else
            throw InputError(file, where + ": option '" + name +
                                       "' must be a string, number, list or true/false");
          addOption(study, name, text);
        }
      } else {
        throw InputError(file, where + ": unknown key '" + key + "' (id, study, task, options)");
      }
    }
    study.study = study.studyText;
    study.line = entry.dump();
    study.lineNumber = index;
    addStudy(manifest, ids, std::move(study), where, known);
  }
  return manifest;
}

}  // namespace

BatchManifest loadBatchManifest(const fs::path& file, const TaskOptions& known) {
  requireReadable(file);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot be read");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  const fs::path absolute = fs::absolute(file).lexically_normal();
  BatchManifest manifest =
      ext == ".json" ? loadJson(absolute, in, known) : loadCsv(absolute, in, known);
  if (manifest.studies.empty()) throw InputError(file, "lists no study");
  return manifest;
}

}  // namespace mvw::batch
