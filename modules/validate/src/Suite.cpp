#include "mvw/validate/Suite.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <set>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"

namespace mvw::validate {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

[[noreturn]] void bad(const fs::path& suite, const std::string& problem) {
  throw InputError(suite, problem);
}

}  // namespace

std::string expandEnvironment(const std::string& s, const fs::path& suite,
                              const std::string& where) {
  std::string out;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s.compare(i, 2, "${") == 0) {
      const std::size_t end = s.find('}', i + 2);
      if (end == std::string::npos) bad(suite, where + ": unterminated ${ in \"" + s + "\"");
      const std::string name = s.substr(i + 2, end - i - 2);
      const char* value = name.empty() ? nullptr : std::getenv(name.c_str());
      if (value == nullptr || *value == '\0')
        bad(suite, where + ": environment variable " + (name.empty() ? "(empty name)" : name) +
                       " is not set");
      out += value;
      i = end + 1;
    } else {
      out += s[i++];
    }
  }
  return out;
}

namespace {

fs::path resolvePath(const json& value, const fs::path& suite, const std::string& where) {
  if (!value.is_string() || value.get<std::string>().empty())
    bad(suite, where + " must be a non-empty string");
  fs::path p = expandEnvironment(value.get<std::string>(), suite, where);
  if (p.is_relative()) p = fs::absolute(suite).parent_path() / p;
  return p.lexically_normal();
}

void checkKeys(const json& object, const std::set<std::string>& allowed, const fs::path& suite,
               const std::string& where) {
  if (!object.is_object()) bad(suite, where + " must be an object");
  for (const auto& [key, value] : object.items()) {
    (void)value;
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      bad(suite, where + ": unknown key \"" + key + "\" (known: " + list + ")");
    }
  }
}

double numberOf(const json& object, const char* key, double fallback, const fs::path& suite,
                const std::string& where, double lo = -std::numeric_limits<double>::infinity(),
                double hi = std::numeric_limits<double>::infinity()) {
  if (!object.contains(key)) return fallback;
  const json& v = object.at(key);
  if (!v.is_number()) bad(suite, where + ": \"" + key + "\" must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi)
    bad(suite, where + ": \"" + key + "\" = " + v.dump() + " is out of range [" +
                   std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return d;
}

Tolerance parseTolerance(const json& t, Tolerance base, const fs::path& suite,
                         const std::string& where) {
  checkKeys(t, {"max_delta", "max_delta_fraction", "mean_delta", "psnr", "ssim"}, suite, where);
  base.maxDelta = numberOf(t, "max_delta", base.maxDelta, suite, where, 0, 255);
  base.maxDeltaFraction =
      numberOf(t, "max_delta_fraction", base.maxDeltaFraction, suite, where, 0, 1);
  base.meanDelta = numberOf(t, "mean_delta", base.meanDelta, suite, where, 0, 255);
  base.psnr = numberOf(t, "psnr", base.psnr, suite, where, 0, 1000);
  base.ssim = numberOf(t, "ssim", base.ssim, suite, where, -1, 1);
  return base;
}

CheckSpec parseCheck(const json& c, const fs::path& suite, const std::string& where) {
  checkKeys(c, {"type", "axis", "window", "level", "min_psnr", "max_worst"}, suite, where);
  CheckSpec s;
  if (!c.contains("type") || !c["type"].is_string())
    bad(suite, where + ": \"type\" (a string) is required");
  s.type = c["type"];
  if (s.type != "mip_equals_max_projection")
    bad(suite,
        where + ": unknown check type \"" + s.type + "\" (known: mip_equals_max_projection)");
  const std::string axis =
      c.contains("axis") && c["axis"].is_string() ? c["axis"].get<std::string>() : "";
  if (axis == "x" || axis == "i")
    s.axis = 0;
  else if (axis == "y" || axis == "j")
    s.axis = 1;
  else if (axis == "z" || axis == "k")
    s.axis = 2;
  else
    bad(suite, where + ": \"axis\" must be one of x, y, z (the volume's index axes i, j, k)");
  if (c.contains("window") != c.contains("level"))
    bad(suite, where + ": \"window\" and \"level\" go together");
  if (c.contains("window")) {
    s.window = numberOf(c, "window", 0, suite, where, 1e-12);
    s.level = numberOf(c, "level", 0, suite, where);
  }
  s.minPsnr = numberOf(c, "min_psnr", s.minPsnr, suite, where, 0, 1000);
  s.maxWorst = numberOf(c, "max_worst", s.maxWorst, suite, where, 0, 255);
  return s;
}

}  // namespace

bool isGoodCaseName(const std::string& n) {
  if (n.empty() || n.size() > 100 || n[0] == '.') return false;
  return std::all_of(n.begin(), n.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.';
  });
}

Suite loadSuite(const fs::path& file) {
  if (fs::is_directory(file)) bad(file, "is a folder, not a suite file (.json)");
  if (const std::string why = whyUnreadable(file); !why.empty()) bad(file, why);
  std::ifstream in(file);
  if (!in) bad(file, "cannot be opened");
  json root;
  try {
    root = config::parseJson(in, file);
  } catch (const json::parse_error& e) {
    bad(file, std::string("not valid JSON: ") + e.what());
  }
  Suite suite;
  suite.file = file;
  checkKeys(root, {"name", "description", "study", "tolerance", "checksums", "cases"}, file,
            "suite");
  if (root.contains("name")) {
    if (!root["name"].is_string()) bad(file, "\"name\" must be a string");
    suite.name = root["name"];
  }
  if (root.contains("checksums"))
    suite.checksums = resolvePath(root["checksums"], file, "\"checksums\"");
  std::optional<fs::path> defaultStudy;
  if (root.contains("study")) defaultStudy = resolvePath(root["study"], file, "\"study\"");
  Tolerance defaults;
  if (root.contains("tolerance"))
    defaults = parseTolerance(root["tolerance"], defaults, file, "\"tolerance\"");
  if (!root.contains("cases") || !root["cases"].is_array() || root["cases"].empty())
    bad(file, "\"cases\" must be a non-empty list");
  std::set<std::string> names;
  int index = 0;
  for (const json& c : root["cases"]) {
    ++index;
    std::string where = "case " + std::to_string(index);
    checkKeys(c, {"name", "description", "study", "view", "reference", "tolerance", "checks"}, file,
              where);
    CaseSpec cs;
    if (!c.contains("name") || !c["name"].is_string() || !isGoodCaseName(c["name"]))
      bad(file,
          where +
              ": \"name\" is required: letters, digits, '-', '_' or '.' (it names report files)");
    cs.name = c["name"];
    where = "case '" + cs.name + "'";
    if (!names.insert(cs.name).second) bad(file, where + ": the name is used twice");
    if (c.contains("study"))
      cs.study = resolvePath(c["study"], file, where + " \"study\"");
    else if (defaultStudy)
      cs.study = *defaultStudy;
    else
      bad(file, where + ": no \"study\" (in the case or at the top of the suite)");
    if (!c.contains("view"))
      bad(file, where + ": \"view\" (a view name of the study or a view object) is required");
    const json& v = c["view"];
    if (v.is_string()) {
      cs.viewLabel = v.get<std::string>();
      cs.view = v;  // resolved against the study below
    } else if (v.is_object()) {
      cs.viewLabel = "(inline)";
      cs.view = v;
    } else {
      bad(file, where + ": \"view\" must be a view name of the study or a view object");
    }
    if (c.contains("reference"))
      cs.reference = resolvePath(c["reference"], file, where + " \"reference\"");
    cs.tolerance = c.contains("tolerance")
                       ? parseTolerance(c["tolerance"], defaults, file, where + " \"tolerance\"")
                       : defaults;
    if (c.contains("checks")) {
      if (!c["checks"].is_array()) bad(file, where + ": \"checks\" must be a list");
      int k = 0;
      for (const json& ch : c["checks"])
        cs.checks.push_back(parseCheck(ch, file, where + " check " + std::to_string(++k)));
    }
    if (!cs.reference && cs.checks.empty())
      bad(file, where + ": give a \"reference\" image, \"checks\", or both");
    suite.cases.push_back(std::move(cs));
  }
  return suite;
}

}  // namespace mvw::validate
