#include "ValidateCommand.h"

#include "StudyVolumes.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/PngWriter.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Camera.h"

extern char** environ;

namespace mvw::app {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ValidateOptions {
  std::string suite;
  std::string outDir;
  bool update = false;
  int jobs = 1;
  double timeoutS = 600.0;
};

// ---------------------------------------------------------------------------------------
// The suite file

struct Tolerance {
  double maxDelta = 24.0;           // per-pixel channel delta (0..255) ...
  double maxDeltaFraction = 0.001;  // ... that at most this fraction of pixels may exceed
  double meanDelta = 0.5;           // mean absolute channel delta
  double psnr = 40.0;               // dB, at least
  double ssim = 0.99;               // grey-level SSIM (Wang et al. 2004), at least
};

// "mip_equals_max_projection": a MIP along a volume index axis, one ray per voxel column,
// against the maximum of the voxel values along that axis computed here from the volume.
struct CheckSpec {
  std::string type;
  int axis = 2;
  std::optional<double> window, level;
  double minPsnr = 35.0;
  double maxWorst = 2.0;  // grey levels, over pixels whose voxel is unambiguous
};

struct CaseSpec {
  std::string name;
  fs::path study;
  json view;              // the view object given to `mvw render`
  std::string viewLabel;  // how the suite named it
  std::optional<fs::path> reference;
  Tolerance tolerance;
  std::vector<CheckSpec> checks;
};

struct Suite {
  fs::path file;
  std::string name;
  std::vector<CaseSpec> cases;
};

[[noreturn]] void bad(const fs::path& suite, const std::string& problem) {
  throw InputError(suite, problem);
}

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

bool goodName(const std::string& n) {
  if (n.empty() || n.size() > 100 || n[0] == '.') return false;
  return std::all_of(n.begin(), n.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.';
  });
}

Suite loadSuite(const fs::path& file) {
  if (!fs::exists(file)) bad(file, "no such file");
  if (fs::is_directory(file)) bad(file, "is a folder, not a suite file (.json)");
  std::ifstream in(file);
  if (!in) bad(file, "cannot be opened");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    bad(file, std::string("not valid JSON: ") + e.what());
  }
  Suite suite;
  suite.file = file;
  checkKeys(root, {"name", "description", "study", "tolerance", "cases"}, file, "suite");
  if (root.contains("name")) {
    if (!root["name"].is_string()) bad(file, "\"name\" must be a string");
    suite.name = root["name"];
  }
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
    if (!c.contains("name") || !c["name"].is_string() || !goodName(c["name"]))
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

// ---------------------------------------------------------------------------------------
// Files: everything the report holds is written to a temporary name and renamed.

fs::path tempNameFor(const fs::path& path) {
  return path.parent_path() /
         ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()));
}

void writeTextAtomic(const fs::path& path, const std::string& text) {
  const fs::path tmp = tempNameFor(path);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f << text;
    f.flush();
    if (!f) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw Error("cannot write " + path.string());
    }
  }
  fs::rename(tmp, path);
}

void copyAtomic(const fs::path& from, const fs::path& to) {
  const fs::path tmp = tempNameFor(to);
  std::error_code ec;
  fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error("cannot copy " + from.string() + " to " + to.string());
  }
  fs::rename(tmp, to);
}

// BGR or grey cv::Mat -> RGBA mvw::Image -> io::writePng (atomic).
void writeMatPng(const cv::Mat& m, const fs::path& path) {
  cv::Mat rgba;
  if (m.channels() == 1)
    cv::cvtColor(m, rgba, cv::COLOR_GRAY2RGBA);
  else
    cv::cvtColor(m, rgba, cv::COLOR_BGR2RGBA);
  Image img(rgba.cols, rgba.rows);
  for (int r = 0; r < rgba.rows; ++r)
    std::memcpy(img.pixel(0, r), rgba.ptr(r), static_cast<std::size_t>(rgba.cols) * 4);
  io::writePng(img, path);
}

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string lastLine(const std::string& text) {
  std::string t = text;
  while (!t.empty() && (t.back() == '\n' || t.back() == '\r')) t.pop_back();
  const auto nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

// ---------------------------------------------------------------------------------------
// Image metrics

double ssimGrey(const cv::Mat& a, const cv::Mat& b) {
  // Wang, Bovik, Sheikh, Simoncelli 2004: 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03,
  // L 255, mean over the window positions that lie inside the image ("valid").
  auto grey = [](const cv::Mat& m) {
    cv::Mat g, d;
    if (m.channels() == 3)
      cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
    else
      g = m;
    g.convertTo(d, CV_64F);
    return d;
  };
  const cv::Mat x = grey(a), y = grey(b);
  const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  auto blur = [](const cv::Mat& m) {
    cv::Mat o;
    cv::GaussianBlur(m, o, cv::Size(11, 11), 1.5, 1.5, cv::BORDER_REFLECT);
    return o;
  };
  const cv::Mat mx = blur(x), my = blur(y);
  const cv::Mat mxx = mx.mul(mx), myy = my.mul(my), mxy = mx.mul(my);
  const cv::Mat sxx = blur(x.mul(x)) - mxx, syy = blur(y.mul(y)) - myy, sxy = blur(x.mul(y)) - mxy;
  cv::Mat num = (2 * mxy + c1).mul(2 * sxy + c2);
  cv::Mat den = (mxx + myy + c1).mul(sxx + syy + c2);
  cv::Mat map;
  cv::divide(num, den, map);
  if (map.rows > 10 && map.cols > 10) map = map(cv::Rect(5, 5, map.cols - 10, map.rows - 10));
  return cv::mean(map)[0];
}

struct Metrics {
  double maxDelta = 0, overFraction = 0, meanDelta = 0, psnr = 0, ssim = 0;
  cv::Mat heat;
};

double psnrOf(double mse) {
  return mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
}

cv::Mat heatMap(const cv::Mat& perPixelDelta) {
  // |delta| x 8 on the inferno scale; identical pixels stay black.
  cv::Mat scaled, heat;
  perPixelDelta.convertTo(scaled, CV_8U, 8.0);
  cv::applyColorMap(scaled, heat, cv::COLORMAP_INFERNO);
  heat.setTo(cv::Scalar(0, 0, 0), perPixelDelta == 0);
  return heat;
}

Metrics compareImages(const cv::Mat& actual, const cv::Mat& reference, double deltaThreshold) {
  Metrics m;
  cv::Mat diff;
  cv::absdiff(actual, reference, diff);
  std::vector<cv::Mat> channels;
  cv::split(diff, channels);
  cv::Mat perPixel = channels[0].clone();
  for (std::size_t c = 1; c < channels.size(); ++c) perPixel = cv::max(perPixel, channels[c]);
  cv::minMaxLoc(perPixel, nullptr, &m.maxDelta);
  m.overFraction =
      cv::countNonZero(perPixel > deltaThreshold) / static_cast<double>(perPixel.total());
  cv::Mat d64;
  diff.convertTo(d64, CV_64F);
  const double values = static_cast<double>(diff.total()) * diff.channels();
  m.meanDelta = cv::sum(cv::sum(d64))[0] / values;
  const cv::Scalar sq = cv::sum(d64.mul(d64));
  m.psnr = psnrOf((sq[0] + sq[1] + sq[2] + sq[3]) / values);
  m.ssim = ssimGrey(actual, reference);
  m.heat = heatMap(perPixel);
  return m;
}

json numberOrInf(double v) { return std::isfinite(v) ? json(v) : json("inf"); }

std::string fmt(double v, int digits) {
  if (!std::isfinite(v)) return "inf";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

// ---------------------------------------------------------------------------------------
// The analytic MIP check: geometry chosen so that every pixel's ray runs along one voxel
// column (index axis `axis`), sampled with nearest lookup at every voxel centre.

struct MipPlan {
  json view;
  glm::ivec2 size{0};
  render::Camera camera;
  int a = 0, b = 1;  // index axes along the screen's right and up
};

MipPlan planMip(const Volume& v, const CheckSpec& c, const fs::path& suite,
                const std::string& where) {
  const glm::dmat3 dir = v.direction();
  const glm::dvec3 col = dir[c.axis];
  int w = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(col[k]) > std::abs(col[w])) w = k;
  if (std::abs(col[w]) < 0.9999)
    bad(suite, where + ": the volume's index axis " + "ijk"[c.axis] +
                   " is oblique to the LPS axes; "
                   "mip_equals_max_projection needs an axis-aligned one");
  render::CameraSettings cs;
  cs.view = w == 0   ? render::StandardView::Left
            : w == 1 ? render::StandardView::Anterior
                     : render::StandardView::Superior;
  const glm::ivec3 d = v.dimensions();
  const glm::dvec3 sp = v.spacing();
  // The renderer's framing: the bounding sphere of the voxel box around its centre.
  const glm::dvec3 corner0 = glm::dvec3(v.worldFromIndex() * glm::dvec4(-0.5, -0.5, -0.5, 1.0));
  const glm::dvec3 corner1 = glm::dvec3(v.worldFromIndex() * glm::dvec4(glm::dvec3(d) - 0.5, 1.0));
  const glm::dvec3 centre = 0.5 * (corner0 + corner1);
  const double radius = 0.5 * glm::length(glm::dvec3(d) * sp);
  const render::Camera probe = render::makeCamera(cs, centre, radius, {1, 1});
  auto along = [&](const glm::dvec3& s) {
    for (int k = 0; k < 3; ++k)
      if (k != c.axis && std::abs(glm::dot(dir[k], s)) > 0.9999) return k;
    return -1;
  };
  MipPlan p;
  p.a = along(probe.right);
  p.b = along(probe.up);
  if (p.a < 0 || p.b < 0)
    bad(suite, where + ": the volume's in-plane axes are oblique to the view");
  const double pixelMm = std::min(sp[p.a], sp[p.b]);
  p.size = {static_cast<int>(std::max(1L, std::lround(d[p.a] * sp[p.a] / pixelMm))),
            static_cast<int>(std::max(1L, std::lround(d[p.b] * sp[p.b] / pixelMm)))};
  if (p.size.x > 8192 || p.size.y > 8192)
    bad(suite, where + ": the volume needs a " + std::to_string(p.size.x) + " x " +
                   std::to_string(p.size.y) + " image (more than 8192 pixels a side)");
  const double aspect = static_cast<double>(p.size.x) / p.size.y;
  cs.zoom = radius / std::min(1.0, aspect) / (0.5 * p.size.y * pixelMm);
  p.camera = render::makeCamera(cs, centre, radius, p.size);
  p.view = {{"name", "render"},      {"mode", "mip"},      {"view", render::toString(cs.view)},
            {"width", p.size.x},     {"height", p.size.y}, {"zoom", cs.zoom},
            {"step_mm", sp[c.axis]}, {"jitter", false},    {"sampling", "nearest"},
            {"annotate", false}};
  if (c.window) {
    p.view["window"] = *c.window;
    p.view["level"] = *c.level;
  }
  return p;
}

struct CheckResult {
  bool pass = false;
  std::string message;
  double psnr = 0, worst = 0;
  long pixels = 0, unambiguous = 0;
};

CheckResult evaluateMip(const Volume& v, const CheckSpec& c, const MipPlan& p,
                        const cv::Mat& rendered, cv::Mat& expectedOut, cv::Mat& heatOut) {
  CheckResult r;
  const glm::ivec3 d = v.dimensions();
  double lo = 0, hi = 0;
  if (c.window) {
    lo = *c.level - 0.5 * *c.window;
    hi = *c.level + 0.5 * *c.window;
  } else {
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          const double x = v.value(i, j, k);
          if (std::isnan(x)) continue;
          lo = std::min(lo, x);
          hi = std::max(hi, x);
        }
    if (!(hi > lo)) hi = lo + 1.0;
  }
  cv::Mat expected(p.size.y, p.size.x, CV_8U, cv::Scalar(0));
  cv::Mat delta(p.size.y, p.size.x, CV_8U, cv::Scalar(0));
  const glm::dmat4 indexFromWorld = glm::inverse(v.worldFromIndex());
  double se = 0;
  for (int row = 0; row < p.size.y; ++row)
    for (int col = 0; col < p.size.x; ++col) {
      const glm::dvec2 ndc((col + 0.5) / p.size.x * 2 - 1, 1 - (row + 0.5) / p.size.y * 2);
      const glm::dvec4 w = p.camera.worldFromClip * glm::dvec4(ndc, 0.0, 1.0);
      const glm::dvec3 idx = glm::dvec3(indexFromWorld * glm::dvec4(glm::dvec3(w) / w.w, 1.0));
      const long ia = std::lround(idx[p.a]), ib = std::lround(idx[p.b]);
      if (ia < 0 || ib < 0 || ia >= d[p.a] || ib >= d[p.b]) continue;
      // A pixel centre on a voxel boundary may go either way in the GL's nearest lookup.
      auto ambiguous = [](double f) { return std::abs(f - std::floor(f) - 0.5) < 0.02; };
      const bool sure = !ambiguous(idx[p.a]) && !ambiguous(idx[p.b]);
      double m = -std::numeric_limits<double>::infinity();
      glm::ivec3 ijk(0);
      ijk[p.a] = static_cast<int>(ia);
      ijk[p.b] = static_cast<int>(ib);
      for (int t = 0; t < d[c.axis]; ++t) {
        ijk[c.axis] = t;
        const double x = v.value(ijk.x, ijk.y, ijk.z);
        if (!std::isnan(x)) m = std::max(m, x);
      }
      const double e = std::clamp((m - lo) / (hi - lo), 0.0, 1.0) * 255.0;
      const double got = rendered.at<cv::Vec3b>(row, col)[2];  // red
      expected.at<std::uint8_t>(row, col) = static_cast<std::uint8_t>(std::lround(e));
      const double err = std::abs(got - e);
      delta.at<std::uint8_t>(row, col) =
          static_cast<std::uint8_t>(std::min(255.0, std::round(err)));
      se += err * err;
      ++r.pixels;
      if (sure) {
        ++r.unambiguous;
        r.worst = std::max(r.worst, err);
      }
    }
  expectedOut = expected;
  heatOut = heatMap(delta);
  if (r.pixels == 0) {
    r.message = "no pixel of the render falls on the volume";
    return r;
  }
  r.psnr = psnrOf(se / r.pixels);
  r.pass = r.psnr >= c.minPsnr && r.worst <= c.maxWorst;
  r.message = "MIP along " + std::string(1, "ijk"[c.axis]) + " vs the maximum projection: PSNR " +
              fmt(r.psnr, 2) + " dB (min " + fmt(c.minPsnr, 1) + "), worst " + fmt(r.worst, 1) +
              "/255 (max " + fmt(c.maxWorst, 1) + ") over " + std::to_string(r.unambiguous) +
              " of " + std::to_string(r.pixels) + " pixels";
  return r;
}

// ---------------------------------------------------------------------------------------
// Rendering: `mvw render` in a child process per job, N at a time.

struct Job {
  std::size_t caseIndex = 0;
  int check = -1;  // -1: the case's image; else the index of its analytic check
  fs::path study, out, log;
  int status = -1;  // exit code; 124 = timed out, 1 = crashed
  double seconds = 0;
};

pid_t spawnRender(const fs::path& exe, const Job& job) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, job.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<std::string> args = {exe.string(), "render", job.study.string(), "-o",
                                   job.out.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw Error("cannot start " + exe.string() + ": " + std::strerror(rc));
  return pid;
}

// ---------------------------------------------------------------------------------------
// Results and the report

struct CaseResult {
  bool pass = true;
  bool updated = false;
  std::vector<std::string> problems;
  std::optional<Metrics> metrics;
  std::vector<CheckResult> checks;
  double seconds = 0;
  bool hasRender = false, hasReference = false, hasDiff = false;
};

std::string html(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return b;
}

std::string hostName() {
  char b[256] = {};
  if (::gethostname(b, sizeof b - 1) != 0) return "?";
  return b;
}

void progressBar(std::size_t done, std::size_t total, bool tty) {
  if (!tty) return;
  const int width = 30;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << done
            << "/" << total << " cases" << std::flush;
}

std::string caseLine(const CaseSpec& c, const CaseResult& r) {
  std::string s = (r.updated ? "UPDATED " : r.pass ? "PASS    " : "FAIL    ") + c.name;
  if (r.metrics)
    s += "  max " + fmt(r.metrics->maxDelta, 0) + " (" + fmt(100 * r.metrics->overFraction, 3) +
         "% > " + fmt(c.tolerance.maxDelta, 0) + ")  mean " + fmt(r.metrics->meanDelta, 3) +
         "  PSNR " + fmt(r.metrics->psnr, 2) + " dB  SSIM " + fmt(r.metrics->ssim, 4);
  for (const auto& ch : r.checks) s += std::string("  check ") + (ch.pass ? "ok" : "FAILED");
  s += "  (" + fmt(r.seconds, 1) + " s)";
  for (const auto& p : r.problems) s += "\n          " + p;
  return s;
}

// True when every case passes.
bool runValidate(const ValidateOptions& o) {
  const Suite suite = loadSuite(o.suite);

  // Every study config and view is checked before anything renders.
  const fs::path work = fs::temp_directory_path() / ("mvw-validate-" + std::to_string(::getpid()));
  struct WorkCleanup {
    fs::path dir;
    ~WorkCleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{work};
  fs::remove_all(work);
  fs::create_directories(work);

  std::map<fs::path, config::StudyConfig> studies;
  std::map<fs::path, json> rawStudies;
  std::map<fs::path, Volume> volumes;
  std::vector<Job> jobs;
  std::vector<std::vector<MipPlan>> plans(suite.cases.size());
  for (std::size_t ci = 0; ci < suite.cases.size(); ++ci) {
    const CaseSpec& c = suite.cases[ci];
    const std::string where = "case '" + c.name + "'";
    if (!studies.count(c.study)) {
      try {
        studies.emplace(c.study, config::loadStudyConfig(c.study));
      } catch (const InputError& e) {
        bad(suite.file, where + ": study config " + e.what());
      }
      rawStudies[c.study] = json::parse(std::ifstream(c.study));
    }
    const config::StudyConfig& study = studies.at(c.study);
    json base = rawStudies.at(c.study);
    base["anatomical"]["path"] = fs::absolute(study.anatomical.path).string();
    if (study.functional)
      base["functional"]["path"] = fs::absolute(study.functional->path).string();

    auto makeJob = [&](const json& view, int check) {
      Job j;
      j.caseIndex = ci;
      j.check = check;
      const fs::path dir =
          work / (c.name + (check < 0 ? std::string() : "-check" + std::to_string(check)));
      fs::create_directories(dir);
      json s = base;
      json v = view;
      v["name"] = "render";
      s["render"] = {{"views", json::array({v})}};
      j.study = dir / "study.json";
      j.out = dir / "out";
      j.log = dir / "render.log";
      std::ofstream(j.study) << s.dump(2) << "\n";
      try {
        (void)config::loadStudyConfig(j.study);
      } catch (const InputError& e) {
        bad(suite.file, where + ": view " +
                            (check < 0 ? c.viewLabel : "of check " + std::to_string(check + 1)) +
                            ": " + e.problem());
      }
      jobs.push_back(j);
    };

    if (c.reference) {
      json view = c.view;
      if (view.is_string()) {
        const std::string wanted = view;
        json found;
        std::string known;
        if (base.contains("render") && base["render"].contains("views"))
          for (const json& sv : base["render"]["views"]) {
            const std::string n = sv.value("name", "");
            known += (known.empty() ? "" : ", ") + n;
            if (n == wanted) found = sv;
          }
        if (found.is_null())
          bad(suite.file, where + ": the study " + c.study.string() + " has no view named \"" +
                              wanted + "\" (it has: " + (known.empty() ? "none" : known) + ")");
        view = found;
      }
      makeJob(view, -1);
    }
    for (std::size_t k = 0; k < c.checks.size(); ++k) {
      const fs::path& anatomical = study.anatomical.path;
      if (!volumes.count(anatomical)) volumes.emplace(anatomical, readSource(study.anatomical));
      plans[ci].push_back(planMip(volumes.at(anatomical), c.checks[k], suite.file,
                                  where + " check " + std::to_string(k + 1)));
      makeJob(plans[ci].back().view, static_cast<int>(k));
    }
  }

  // Render.
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  const fs::path report = o.outDir;
  {
    std::error_code ec;
    fs::create_directories(report / "cases", ec);
    if (ec) throw InputError(report, "cannot create the report folder: " + ec.message());
  }
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  std::vector<CaseResult> results(suite.cases.size());
  std::vector<int> pending(suite.cases.size(), 0);
  for (const Job& j : jobs) ++pending[j.caseIndex];
  json environment = {{"mvw_version", nullptr}, {"gl_renderer", nullptr}, {"gl_version", nullptr}};
  std::size_t casesDone = 0;

  auto finishCase = [&](std::size_t ci) {
    const CaseSpec& c = suite.cases[ci];
    CaseResult& r = results[ci];
    const fs::path dir = report / "cases" / c.name;
    fs::create_directories(dir);
    for (const Job& j : jobs) {
      if (j.caseIndex != ci) continue;
      r.seconds += j.seconds;
      const std::string tag = j.check < 0 ? "" : "check" + std::to_string(j.check + 1) + "-";
      copyAtomic(j.log, dir / (tag + "render.log"));
      const fs::path png = j.out / "render.png";
      if (j.status != 0 || !fs::exists(png)) {
        r.pass = false;
        const std::string why = j.status == 124
                                    ? "timed out after " + fmt(o.timeoutS, 0) + " s"
                                    : "mvw render exited with " + std::to_string(j.status);
        r.problems.push_back(
            (j.check < 0 ? "render: " : "check " + std::to_string(j.check + 1) + " render: ") +
            why + ": " + lastLine(readText(j.log)));
        if (j.check >= 0) r.checks.push_back(CheckResult{false, "not rendered", 0, 0, 0, 0});
        continue;
      }
      if (environment["gl_renderer"].is_null()) {
        try {
          const json rj = json::parse(std::ifstream(j.out / "render.json"));
          environment["gl_renderer"] = rj.value("gl_renderer", "");
          environment["gl_version"] = rj.value("gl_version", "");
          environment["mvw_version"] = rj.value("mvw_version", "");
        } catch (const json::exception&) {
        }
      }
      const cv::Mat rendered = cv::imread(png.string(), cv::IMREAD_COLOR);
      if (rendered.empty()) {
        r.pass = false;
        r.problems.push_back("the render " + png.string() + " cannot be read");
        continue;
      }
      if (j.check >= 0) {
        const CheckSpec& spec = c.checks[static_cast<std::size_t>(j.check)];
        const Volume& v = volumes.at(studies.at(c.study).anatomical.path);
        cv::Mat expected, heat;
        CheckResult cr = evaluateMip(v, spec, plans[ci][static_cast<std::size_t>(j.check)],
                                     rendered, expected, heat);
        writeMatPng(expected, dir / (tag + "expected.png"));
        copyAtomic(png, dir / (tag + "render.png"));
        writeMatPng(heat, dir / (tag + "diff.png"));
        if (!cr.pass) {
          r.pass = false;
          r.problems.push_back("check " + std::to_string(j.check + 1) + ": " + cr.message);
        }
        r.checks.push_back(cr);
        continue;
      }
      copyAtomic(png, dir / "render.png");
      r.hasRender = true;
      const fs::path& ref = *c.reference;
      const bool refExists = fs::exists(ref);
      cv::Mat reference;
      if (refExists) reference = cv::imread(ref.string(), cv::IMREAD_COLOR);
      if (refExists && !reference.empty() && reference.size() == rendered.size()) {
        r.metrics = compareImages(rendered, reference, c.tolerance.maxDelta);
        writeMatPng(r.metrics->heat, dir / "diff.png");
        r.hasDiff = true;
      }
      if (o.update) {
        fs::create_directories(ref.parent_path());
        copyAtomic(png, ref);
        r.updated = true;
        copyAtomic(png, dir / "reference.png");
        r.hasReference = true;
        continue;
      }
      if (!refExists) {
        r.pass = false;
        r.problems.push_back("reference " + ref.string() + " is missing (--update writes it)");
        continue;
      }
      if (reference.empty()) {
        r.pass = false;
        r.problems.push_back("reference " + ref.string() + " is not a readable image");
        continue;
      }
      copyAtomic(ref, dir / "reference.png");
      r.hasReference = true;
      if (reference.size() != rendered.size()) {
        r.pass = false;
        r.problems.push_back("size " + std::to_string(rendered.cols) + " x " +
                             std::to_string(rendered.rows) + " differs from the reference's " +
                             std::to_string(reference.cols) + " x " +
                             std::to_string(reference.rows));
        continue;
      }
      const Metrics& m = *r.metrics;
      const Tolerance& t = c.tolerance;
      if (m.overFraction > t.maxDeltaFraction)
        r.problems.push_back(fmt(100 * m.overFraction, 3) + "% of pixels differ by more than " +
                             fmt(t.maxDelta, 0) + " (allowed " + fmt(100 * t.maxDeltaFraction, 3) +
                             "%)");
      if (m.meanDelta > t.meanDelta)
        r.problems.push_back("mean delta " + fmt(m.meanDelta, 3) + " > " + fmt(t.meanDelta, 3));
      if (m.psnr < t.psnr)
        r.problems.push_back("PSNR " + fmt(m.psnr, 2) + " dB < " + fmt(t.psnr, 2) + " dB");
      if (m.ssim < t.ssim) r.problems.push_back("SSIM " + fmt(m.ssim, 4) + " < " + fmt(t.ssim, 4));
      if (!r.problems.empty()) r.pass = false;
    }
    ++casesDone;
    if (tty) std::cerr << "\r\033[K";
    std::cout << caseLine(c, r) << std::endl;
    progressBar(casesDone, suite.cases.size(), tty);
  };

  struct Running {
    pid_t pid;
    std::size_t job;
    std::chrono::steady_clock::time_point start;
  };
  std::vector<Running> running;
  std::size_t next = 0;
  progressBar(0, suite.cases.size(), tty);
  while (next < jobs.size() || !running.empty()) {
    while (static_cast<int>(running.size()) < o.jobs && next < jobs.size()) {
      running.push_back({spawnRender(exe, jobs[next]), next, std::chrono::steady_clock::now()});
      ++next;
    }
    bool reaped = false;
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
      pid_t got = ::waitpid(it->pid, &status, WNOHANG);
      Job& j = jobs[it->job];
      if (got == 0 && seconds > o.timeoutS) {
        ::kill(it->pid, SIGKILL);
        ::waitpid(it->pid, &status, 0);
        j.status = 124;
        got = it->pid;
      } else if (got == it->pid) {
        j.status = WIFEXITED(status) ? WEXITSTATUS(status)
                                     : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
      } else if (got < 0) {
        j.status = 1;
        got = it->pid;
      }
      if (got == 0) {
        ++it;
        continue;
      }
      j.seconds = seconds;
      reaped = true;
      const std::size_t ci = j.caseIndex;
      it = running.erase(it);
      if (--pending[ci] == 0) finishCase(ci);
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (tty) std::cerr << "\n";

  // The report.
  int passed = 0;
  for (const auto& r : results) passed += r.pass ? 1 : 0;
  const int failed = static_cast<int>(results.size()) - passed;
  environment["host"] = hostName();
  environment["date_utc"] = utcNow();
  environment["jobs"] = o.jobs;
  json rj;
  rj["suite"] = fs::absolute(suite.file).string();
  rj["name"] = suite.name;
  rj["environment"] = environment;
  rj["passed"] = passed;
  rj["failed"] = failed;
  rj["updated"] = o.update;
  rj["cases"] = json::array();
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>mvw validate: "
    << html(suite.name)
    << "</title>\n<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}img{image-rendering:pixelated;"
       "width:256px;background:#222}.pass{color:#080;font-weight:bold}.fail{color:#c00;font-weight:"
       "bold}"
       ".case{margin:1.5em 0;border-top:2px solid "
       "#888;padding-top:.5em}figure{display:inline-block;margin:4px}"
       "</style></head><body>\n";
  h << "<h1>mvw validate: "
    << html(suite.name.empty() ? suite.file.filename().string() : suite.name) << "</h1>\n";
  h << "<p class=\"" << (failed ? "fail" : "pass") << "\">" << passed << " of " << results.size()
    << " cases pass" << (o.update ? " (references updated)" : "") << "</p>\n";
  h << "<h2>Environment</h2><table>";
  h << "<tr><th>suite</th><td>" << html(fs::absolute(suite.file).string()) << "</td></tr>";
  for (const char* key : {"mvw_version", "gl_renderer", "gl_version", "host", "date_utc", "jobs"}) {
    const json& v = environment[key];
    h << "<tr><th>" << key << "</th><td>" << html(v.is_string() ? v.get<std::string>() : v.dump())
      << "</td></tr>";
  }
  h << "</table>\n<h2>Cases</h2>\n<table><tr><th>case</th><th>result</th><th>max delta</th><th>% "
       "over</th>"
       "<th>mean delta</th><th>PSNR dB</th><th>SSIM</th><th>checks</th></tr>\n";
  for (std::size_t ci = 0; ci < suite.cases.size(); ++ci) {
    const CaseSpec& c = suite.cases[ci];
    const CaseResult& r = results[ci];
    h << "<tr><td><a href=\"#" << html(c.name) << "\">" << html(c.name) << "</a></td><td class=\""
      << (r.pass ? "pass" : "fail") << "\">"
      << (r.updated ? "updated"
          : r.pass  ? "pass"
                    : "FAIL")
      << "</td>";
    if (r.metrics)
      h << "<td>" << fmt(r.metrics->maxDelta, 0) << "</td><td>"
        << fmt(100 * r.metrics->overFraction, 3) << "</td><td>" << fmt(r.metrics->meanDelta, 3)
        << "</td><td>" << fmt(r.metrics->psnr, 2) << "</td><td>" << fmt(r.metrics->ssim, 4)
        << "</td>";
    else
      h << "<td colspan=\"5\">-</td>";
    int okChecks = 0;
    for (const auto& ch : r.checks) okChecks += ch.pass ? 1 : 0;
    h << "<td>" << okChecks << "/" << c.checks.size() << "</td></tr>\n";
  }
  h << "</table>\n";
  for (std::size_t ci = 0; ci < suite.cases.size(); ++ci) {
    const CaseSpec& c = suite.cases[ci];
    const CaseResult& r = results[ci];
    const std::string dir = "cases/" + c.name + "/";
    json cj;
    cj["name"] = c.name;
    cj["study"] = c.study.string();
    cj["view"] = c.viewLabel;
    cj["pass"] = r.pass;
    cj["updated"] = r.updated;
    cj["seconds"] = r.seconds;
    cj["problems"] = r.problems;
    if (c.reference) cj["reference"] = c.reference->string();
    cj["tolerance"] = {{"max_delta", c.tolerance.maxDelta},
                       {"max_delta_fraction", c.tolerance.maxDeltaFraction},
                       {"mean_delta", c.tolerance.meanDelta},
                       {"psnr", c.tolerance.psnr},
                       {"ssim", c.tolerance.ssim}};
    if (r.metrics)
      cj["metrics"] = {{"max_delta", r.metrics->maxDelta},
                       {"fraction_over_max_delta", r.metrics->overFraction},
                       {"mean_delta", r.metrics->meanDelta},
                       {"psnr_db", numberOrInf(r.metrics->psnr)},
                       {"ssim", r.metrics->ssim}};
    cj["checks"] = json::array();
    h << "<div class=\"case\" id=\"" << html(c.name) << "\"><h3>" << html(c.name)
      << " <span class=\"" << (r.pass ? "pass" : "fail") << "\">"
      << (r.updated ? "updated"
          : r.pass  ? "pass"
                    : "FAIL")
      << "</span></h3>\n";
    h << "<p>study " << html(c.study.string()) << ", view " << html(c.viewLabel);
    if (c.reference) h << ", reference " << html(c.reference->string());
    h << " (" << fmt(r.seconds, 1) << " s)</p>\n";
    for (const auto& p : r.problems) h << "<p class=\"fail\">" << html(p) << "</p>\n";
    if (c.reference) {
      if (r.hasReference)
        h << "<figure><img src=\"" << html(dir)
          << "reference.png\"><figcaption>reference</figcaption></figure>";
      if (r.hasRender)
        h << "<figure><img src=\"" << html(dir)
          << "render.png\"><figcaption>new render</figcaption></figure>";
      if (r.hasDiff)
        h << "<figure><img src=\"" << html(dir)
          << "diff.png\"><figcaption>|delta| x 8</figcaption></figure>";
      h << "\n";
      if (r.metrics) {
        const Metrics& m = *r.metrics;
        const Tolerance& t = c.tolerance;
        h << "<table><tr><th>metric</th><th>value</th><th>tolerance</th></tr>"
          << "<tr><td>max per-pixel delta</td><td>" << fmt(m.maxDelta, 0) << "</td><td>"
          << fmt(t.maxDelta, 0) << " on at most " << fmt(100 * t.maxDeltaFraction, 3)
          << "% of pixels</td></tr>"
          << "<tr><td>pixels over " << fmt(t.maxDelta, 0) << "</td><td>"
          << fmt(100 * m.overFraction, 3) << "%</td><td>&le; " << fmt(100 * t.maxDeltaFraction, 3)
          << "%</td></tr>"
          << "<tr><td>mean delta</td><td>" << fmt(m.meanDelta, 3) << "</td><td>&le; "
          << fmt(t.meanDelta, 3) << "</td></tr>"
          << "<tr><td>PSNR</td><td>" << fmt(m.psnr, 2) << " dB</td><td>&ge; " << fmt(t.psnr, 2)
          << " dB</td></tr>"
          << "<tr><td>SSIM</td><td>" << fmt(m.ssim, 4) << "</td><td>&ge; " << fmt(t.ssim, 4)
          << "</td></tr></table>\n";
      }
    }
    for (std::size_t k = 0; k < r.checks.size(); ++k) {
      const CheckResult& ch = r.checks[k];
      const std::string tag = dir + "check" + std::to_string(k + 1) + "-";
      cj["checks"].push_back({{"type", c.checks[k].type},
                              {"pass", ch.pass},
                              {"message", ch.message},
                              {"psnr_db", numberOrInf(ch.psnr)},
                              {"worst", ch.worst},
                              {"pixels", ch.pixels}});
      h << "<p>check " << k + 1 << " (" << html(c.checks[k].type) << "): <span class=\""
        << (ch.pass ? "pass" : "fail") << "\">" << (ch.pass ? "pass" : "FAIL") << "</span> "
        << html(ch.message) << "</p>\n";
      if (ch.pixels > 0)
        h << "<figure><img src=\"" << html(tag)
          << "expected.png\"><figcaption>maximum projection (computed)</figcaption></figure>"
          << "<figure><img src=\"" << html(tag)
          << "render.png\"><figcaption>MIP render</figcaption></figure>"
          << "<figure><img src=\"" << html(tag)
          << "diff.png\"><figcaption>|delta| x 8</figcaption></figure>\n";
    }
    h << "</div>\n";
    rj["cases"].push_back(cj);
  }
  h << "</body></html>\n";
  writeTextAtomic(report / "report.json", rj.dump(2) + "\n");
  writeTextAtomic(report / "index.html", h.str());
  std::cout << (failed ? "FAILED: " : "passed: ") << passed << " of " << results.size()
            << " cases pass" << (o.update ? " (references updated)" : "") << "; report "
            << (report / "index.html").string() << std::endl;
  return failed == 0;
}

}  // namespace

void addValidateCommand(CLI::App& app) {
  auto o = std::make_shared<ValidateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Render a validation suite headless, compare with reference images, write an HTML report");
  cmd->add_option("suite", o->suite, "Suite file (.json)")->required();
  cmd->add_option("-o,--output", o->outDir, "Report folder (index.html, report.json, cases/)")
      ->required();
  cmd->add_flag("--update", o->update,
                "Rewrite the reference images with the new renders (review them!)");
  cmd->add_option("-j,--jobs", o->jobs, "Cases rendered in parallel processes")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--timeout", o->timeoutS, "Seconds one render may take")
      ->check(CLI::PositiveNumber);
  cmd->callback([o] {
    if (!runValidate(*o)) {
      // A failing case is neither bad input nor an internal fault: exit 1 without a message.
      std::cout.flush();
      std::exit(1);
    }
  });
}

}  // namespace mvw::app
