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

double numberField(const fs::path& file, const json& o, const std::string& where, const std::string& key,
                   double fallback, double lo, double hi) {
  if (!o.contains(key)) return fallback;
  if (!o[key].is_number()) throw InputError(file, "'" + where + key + "' must be a number");
  const double v = o[key].get<double>();
  if (!(v >= lo && v <= hi))
    throw InputError(file, "'" + where + key + "' = " + std::to_string(v) + " is outside " + std::to_string(lo) +
                               " .. " + std::to_string(hi));
  return v;
}

bool boolField(const fs::path& file, const json& o, const std::string& where, const std::string& key, bool fallback) {
  if (!o.contains(key)) return fallback;
  if (!o[key].is_boolean()) throw InputError(file, "'" + where + key + "' must be true or false");
  return o[key].get<bool>();
}

std::array<double, 3> tripleField(const fs::path& file, const json& o, const std::string& where,
                                  const std::string& key, std::array<double, 3> fallback, double lo, double hi) {
  if (!o.contains(key)) return fallback;
  const json& a = o[key];
  if (!a.is_array() || a.size() != 3) throw InputError(file, "'" + where + key + "' must be an array of 3 numbers");
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i) {
    if (!a[i].is_number()) throw InputError(file, "'" + where + key + "' must be an array of 3 numbers");
    out[i] = a[i].get<double>();
    if (!(out[i] >= lo && out[i] <= hi))
      throw InputError(file, "'" + where + key + "' values must lie in " + std::to_string(lo) + " .. " + std::to_string(hi));
  }
  return out;
}

ViewConfig viewConfig(const fs::path& file, const json& j, const std::string& where, int index) {
  if (!j.is_object()) throw InputError(file, "'" + where + "' must be an object");
  rejectUnknownKeys(file, j, where + ".",
                    {"name", "mode", "view", "azimuth", "elevation", "roll", "zoom", "perspective", "width", "height",
                     "preset", "window", "level", "iso", "shading", "sampling", "step_mm", "jitter", "seed",
                     "background", "crop_min", "crop_max", "annotate", "plane_offset_mm", "slab_mm", "overlay",
                     "overlay_opacity", "overlay_threshold", "gradient_opacity", "depth_cue", "glyphs", "functional_window", "fusion", "functional_classes", "shells", "shells_disabled", "light"});
  const std::string w = where + ".";
  ViewConfig v;
  v.name = stringField(file, j, w, "name", false);
  if (v.name.empty()) v.name = "view" + std::to_string(index);
  if (v.name.find_first_of("/\\") != std::string::npos || v.name == "." || v.name == "..")
    throw InputError(file, "'" + w + "name' must be a plain file name");
  if (j.contains("mode")) v.mode = stringField(file, j, w, "mode", true);
  if (j.contains("view")) v.view = stringField(file, j, w, "view", true);
  v.azimuth = numberField(file, j, w, "azimuth", 0.0, -3600, 3600);
  v.elevation = numberField(file, j, w, "elevation", 0.0, -3600, 3600);
  v.roll = numberField(file, j, w, "roll", 0.0, -3600, 3600);
  v.zoom = numberField(file, j, w, "zoom", 1.0, 1e-3, 1e3);
  v.perspective = boolField(file, j, w, "perspective", false);
  v.width = static_cast<int>(numberField(file, j, w, "width", 512, 1, 8192));
  v.height = static_cast<int>(numberField(file, j, w, "height", 512, 1, 8192));
  v.preset = stringField(file, j, w, "preset", false);
  if (j.contains("window")) v.window = numberField(file, j, w, "window", 0, 1e-9, 1e12);
  if (j.contains("level")) v.level = numberField(file, j, w, "level", 0, -1e12, 1e12);
  if (v.window.has_value() != v.level.has_value())
    throw InputError(file, "'" + w + "window' and '" + w + "level' go together");
  v.iso = numberField(file, j, w, "iso", 300.0, -1e12, 1e12);
  v.shading = boolField(file, j, w, "shading", true);
  if (j.contains("sampling")) v.sampling = stringField(file, j, w, "sampling", true);
  if (v.sampling != "linear" && v.sampling != "nearest")
    throw InputError(file, "'" + w + "sampling' must be linear or nearest");
  v.stepMm = numberField(file, j, w, "step_mm", 0.0, 0.0, 100.0);
  v.jitter = boolField(file, j, w, "jitter", true);
  v.seed = static_cast<unsigned>(numberField(file, j, w, "seed", 1, 0, 4294967295.0));
  v.background = tripleField(file, j, w, "background", v.background, 0.0, 1.0);
  v.cropMin = tripleField(file, j, w, "crop_min", v.cropMin, 0.0, 1.0);
  v.cropMax = tripleField(file, j, w, "crop_max", v.cropMax, 0.0, 1.0);
  for (int a = 0; a < 3; ++a)
    if (v.cropMin[a] >= v.cropMax[a]) throw InputError(file, "'" + w + "crop_min' must be below 'crop_max'");
  v.annotate = boolField(file, j, w, "annotate", true);
  if (j.contains("light")) {
    const json& l = j["light"];
    if (!l.is_array() || l.size() != 2 || !l[0].is_number() || !l[1].is_number())
      throw InputError(file, "'" + w + "light' must be [right, up] (0, 0 is a headlight)");
    v.light = {l[0].get<double>(), l[1].get<double>()};
  }
  if (j.contains("glyphs")) {
    const json& g = j["glyphs"];
    const std::string gw = w + "glyphs.";
    if (!g.is_object()) throw InputError(file, "'" + w + "glyphs' must be an object");
    rejectUnknownKeys(file, g, gw,
                      {"method", "convexity", "placement", "spacing_mm", "diameter_mm", "min_size",
                       "count", "seed", "map_size", "map_diameter"});
    v.glyphs = true;
    if (g.contains("method")) v.glyphMethod = stringField(file, g, gw, "method", true);
    if (v.glyphMethod != "sized" && v.glyphMethod != "simple")
      throw InputError(file, "'" + gw + "method' must be sized or simple");
    if (g.contains("convexity")) v.glyphConvexity = stringField(file, g, gw, "convexity", true);
    if (v.glyphConvexity != "convex" && v.glyphConvexity != "concave" && v.glyphConvexity != "both")
      throw InputError(file, "'" + gw + "convexity' must be convex, concave or both");
    if (g.contains("placement")) v.glyphPlacement = stringField(file, g, gw, "placement", true);
    if (v.glyphPlacement != "blue-noise" && v.glyphPlacement != "paper")
      throw InputError(file, "'" + gw + "placement' must be blue-noise or paper");
    v.glyphSpacingMm = numberField(file, g, gw, "spacing_mm", v.glyphSpacingMm, 0.5, 1000.0);
    v.glyphMinSize = numberField(file, g, gw, "min_size", v.glyphMinSize, 0.0, 1.0);
    // The blue-noise glyph fills most of its spacing; the paper's map its own 6 mm.
    const double diameter = v.glyphPlacement == "paper" ? 6.0 : 0.85 * v.glyphSpacingMm;
    v.glyphDiameterMm = numberField(file, g, gw, "diameter_mm", diameter, 0.1, 1000.0);
    v.glyphCount = static_cast<int>(numberField(file, g, gw, "count", 16, 1, 255));
    v.glyphSeed = static_cast<unsigned>(numberField(file, g, gw, "seed", 1, 0, 4294967295.0));
    v.glyphMapSize = static_cast<int>(numberField(file, g, gw, "map_size", 128, 8, 512));
    v.glyphMapDiameter = numberField(file, g, gw, "map_diameter", 32, 2, 256);
  }
  if (j.contains("functional_window")) {
    const json& fw = j["functional_window"];
    if (!fw.is_array() || fw.size() != 2 || !fw[0].is_number() || !fw[1].is_number() ||
        !(fw[0].get<double>() < fw[1].get<double>()))
      throw InputError(file, "'" + w + "functional_window' must be [low, high] with low < high");
    v.functionalWindow = std::array<double, 2>{fw[0].get<double>(), fw[1].get<double>()};
  }
  if (j.contains("depth_cue")) {
    const json& c = j["depth_cue"];
    if (!c.is_object()) throw InputError(file, "'" + w + "depth_cue' must be an object");
    rejectUnknownKeys(file, c, w + "depth_cue.", {"brightness", "amount", "contrast"});
    v.depthCue = true;
    v.cueBrightness = numberField(file, c, w + "depth_cue.", "brightness", 0.0, 0.0, 10.0);
    v.cueAmount = numberField(file, c, w + "depth_cue.", "amount", 0.0, -10.0, 10.0);
    v.cueContrast = numberField(file, c, w + "depth_cue.", "contrast", 1.0, 0.0, 10.0);
  }
  if (j.contains("gradient_opacity")) {
    const json& g = j["gradient_opacity"];
    if (!g.is_array() || g.size() != 2 || !g[0].is_number() || !g[1].is_number() ||
        !(g[0].get<double>() >= 0.0 && g[0].get<double>() < g[1].get<double>()))
      throw InputError(file, "'" + w + "gradient_opacity' must be [low, high] with 0 <= low < high (unit/mm)");
    v.gradientOpacity = {g[0].get<double>(), g[1].get<double>()};
  }
  v.planeOffsetMm = numberField(file, j, w, "plane_offset_mm", 0.0, -1e4, 1e4);
  v.slabMm = numberField(file, j, w, "slab_mm", 0.0, 0.0, 1e4);
  v.overlay = boolField(file, j, w, "overlay", true);
  v.fusion = boolField(file, j, w, "fusion", false);
  v.shells = static_cast<int>(numberField(file, j, w, "shells", 8, 1, 256));
  if (j.contains("shells_disabled")) {
    const json& d = j["shells_disabled"];
    if (!d.is_array()) throw InputError(file, "'" + w + "shells_disabled' must be an array of shell numbers");
    for (const auto& e : d) {
      if (!e.is_number_integer() || e.get<int>() < 1 || e.get<int>() > v.shells)
        throw InputError(file, "'" + w + "shells_disabled' holds shell numbers 1.." + std::to_string(v.shells));
      v.shellsDisabled.push_back(e.get<int>());
    }
  }
  v.functionalClasses = static_cast<int>(numberField(file, j, w, "functional_classes", 0, 0, 64));
  v.overlayOpacity = numberField(file, j, w, "overlay_opacity", 0.5, 0.0, 1.0);
  v.overlayThreshold = numberField(file, j, w, "overlay_threshold", 0.25, 0.0, 1.0);
  return v;
}

}  // namespace

StudyConfig loadStudyConfig(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open the study config");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {  // parse errors, and numbers too large for a double (406)
    throw InputError(file, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(file, "a study config must be a JSON object");
  rejectUnknownKeys(file, j, "", {"name", "anatomical", "functional", "registration", "render"});
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
  if (j.contains("registration")) {
    const json& g = j["registration"];
    if (!g.is_object()) throw InputError(file, "'registration' must be an object");
    rejectUnknownKeys(file, g, "registration.", {"method", "transform", "rotation_search_deg"});
    if (!config.functional) throw InputError(file, "'registration' needs a 'functional' volume");
    if (g.contains("method")) config.registration.method = stringField(file, g, "registration.", "method", true);
    const std::string& m = config.registration.method;
    if (m != "none" && m != "rigid" && m != "affine" && m != "file")
      throw InputError(file, "'registration.method' must be none, rigid, affine or file");
    const std::string t = stringField(file, g, "registration.", "transform", m == "file");
    if (!t.empty()) {
      config.registration.transform = (fs::path(t).is_absolute() ? fs::path(t) : file.parent_path() / t).lexically_normal();
      std::error_code ec;
      if (m == "file" && !fs::exists(config.registration.transform, ec))
        throw InputError(file, "'registration.transform' names " + config.registration.transform.string() +
                                   ", which does not exist");
    }
    config.registration.rotationSearchDeg = numberField(file, g, "registration.", "rotation_search_deg", 0.0, 0.0, 180.0);
  }
  if (j.contains("render")) {
    const json& r = j["render"];
    if (!r.is_object()) throw InputError(file, "'render' must be an object");
    rejectUnknownKeys(file, r, "render.", {"views"});
    if (r.contains("views")) {
      if (!r["views"].is_array()) throw InputError(file, "'render.views' must be an array");
      for (std::size_t i = 0; i < r["views"].size(); ++i)
        config.render.views.push_back(viewConfig(file, r["views"][i], "render.views[" + std::to_string(i) + "]",
                                                 static_cast<int>(i)));
    }
  }
  if (config.render.views.empty()) {
    ViewConfig defaults;
    defaults.name = "view0";
    config.render.views.push_back(defaults);
  }
  for (std::size_t a = 0; a < config.render.views.size(); ++a)
    for (std::size_t b = a + 1; b < config.render.views.size(); ++b)
      if (config.render.views[a].name == config.render.views[b].name)
        throw InputError(file, "two views are named '" + config.render.views[a].name + "'");
  return config;
}

namespace {

json viewJson(const ViewConfig& v) {
  json j = {{"name", v.name},
            {"mode", v.mode},
            {"view", v.view},
            {"azimuth", v.azimuth},
            {"elevation", v.elevation},
            {"roll", v.roll},
            {"zoom", v.zoom},
            {"perspective", v.perspective},
            {"width", v.width},
            {"height", v.height},
            {"iso", v.iso},
            {"shading", v.shading},
            {"sampling", v.sampling},
            {"step_mm", v.stepMm},
            {"jitter", v.jitter},
            {"seed", v.seed},
            {"background", v.background},
            {"crop_min", v.cropMin},
            {"crop_max", v.cropMax},
            {"annotate", v.annotate},
            {"light", v.light},
            {"plane_offset_mm", v.planeOffsetMm},
            {"slab_mm", v.slabMm},
            {"overlay", v.overlay},
            {"fusion", v.fusion},
            {"overlay_opacity", v.overlayOpacity},
            {"overlay_threshold", v.overlayThreshold},
            {"functional_classes", v.functionalClasses},
            {"shells", v.shells},
            {"shells_disabled", v.shellsDisabled}};
  if (!v.preset.empty()) j["preset"] = v.preset;
  if (v.window) j["window"] = *v.window, j["level"] = *v.level;
  if (v.gradientOpacity[1] > 0.0) j["gradient_opacity"] = v.gradientOpacity;
  if (v.functionalWindow) j["functional_window"] = *v.functionalWindow;
  if (v.glyphs)
    j["glyphs"] = {{"method", v.glyphMethod},         {"convexity", v.glyphConvexity}, {"diameter_mm", v.glyphDiameterMm},
                   {"count", v.glyphCount},           {"seed", v.glyphSeed},           {"map_size", v.glyphMapSize},
                   {"map_diameter", v.glyphMapDiameter}, {"placement", v.glyphPlacement},
                   {"spacing_mm", v.glyphSpacingMm},  {"min_size", v.glyphMinSize}};
  if (v.depthCue) j["depth_cue"] = {{"brightness", v.cueBrightness}, {"amount", v.cueAmount}, {"contrast", v.cueContrast}};
  return j;
}

json sourceJson(const VolumeSource& s) {
  json j = {{"path", fs::absolute(s.path).lexically_normal().string()}};
  if (!s.series.empty()) j["series"] = s.series;
  return j;
}

}  // namespace

void writeStudyConfig(const StudyConfig& config, const fs::path& file) {
  json j;
  j["name"] = config.name;
  j["anatomical"] = sourceJson(config.anatomical);
  if (config.functional) {
    j["functional"] = sourceJson(*config.functional);
    j["functional"]["kind"] = toString(config.functionalKind);
    json r = {{"method", config.registration.method}, {"rotation_search_deg", config.registration.rotationSearchDeg}};
    if (!config.registration.transform.empty())
      r["transform"] = fs::absolute(config.registration.transform).lexically_normal().string();
    j["registration"] = r;
  }
  json views = json::array();
  for (const ViewConfig& v : config.render.views) views.push_back(viewJson(v));
  j["render"] = {{"views", views}};
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) throw Error("cannot write " + tmp.string());
  }
  fs::rename(tmp, file);
}

std::string toString(FunctionalKind kind) {
  for (const auto& [name, k] : kKinds)
    if (k == kind) return name;
  return "other";
}

}  // namespace mvw::config
