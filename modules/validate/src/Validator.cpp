#include "mvw/validate/Validator.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <zlib.h>
#include <opencv2/imgproc.hpp>

#include "Format.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/Png.h"
#include "mvw/output/StudyRender.h"
#include "mvw/process/ProcessPool.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/validate/Checksums.h"
#include "mvw/validate/ImageMetrics.h"
#include "mvw/validate/MipCheck.h"
#include "mvw/validate/Report.h"
#include "mvw/validate/Suite.h"

namespace mvw::validate {

namespace {

namespace fs = std::filesystem;

// Why a file that starts as a PNG cannot be a whole one (truncated, a chunk's CRC wrong, no
// IEND), or nothing. Checked before OpenCV decodes it, because libpng prints its own
// "libpng error: Read Error" on stderr before OpenCV gives up, beside mvw's one message.
std::optional<std::string> pngStructureProblem(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[8] = {};
  if (!in.read(reinterpret_cast<char*>(head), 8) || !std::equal(head, head + 8, kSignature))
    return std::nullopt;  // not a PNG: OpenCV reads other formats, or refuses them quietly
  std::vector<unsigned char> data;
  for (std::uint64_t offset = 8;;) {
    unsigned char lengthAndType[8];
    if (!in.read(reinterpret_cast<char*>(lengthAndType), 8))
      return "it ends at byte " + std::to_string(offset) + " before its IEND chunk (truncated)";
    const std::uint32_t length = (std::uint32_t{lengthAndType[0]} << 24) |
                                 (std::uint32_t{lengthAndType[1]} << 16) |
                                 (std::uint32_t{lengthAndType[2]} << 8) | lengthAndType[3];
    const std::string type(reinterpret_cast<const char*>(lengthAndType) + 4, 4);
    if (length > 0x7fffffffu)
      return "its chunk at byte " + std::to_string(offset) + " claims " + std::to_string(length) +
             " bytes";
    uLong crc = crc32(0L, lengthAndType + 4, 4);
    std::uint32_t left = length;
    while (left > 0) {
      data.resize(std::min<std::uint32_t>(left, 1u << 20));
      if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size())))
        return "its " + type + " chunk at byte " + std::to_string(offset) +
               " runs past the end of the file (truncated)";
      crc = crc32(crc, data.data(), static_cast<uInt>(data.size()));
      left -= static_cast<std::uint32_t>(data.size());
    }
    unsigned char stored[4];
    if (!in.read(reinterpret_cast<char*>(stored), 4))
      return "its " + type + " chunk at byte " + std::to_string(offset) +
             " runs past the end of the file (truncated)";
    const std::uint32_t expected = (std::uint32_t{stored[0]} << 24) |
                                   (std::uint32_t{stored[1]} << 16) |
                                   (std::uint32_t{stored[2]} << 8) | stored[3];
    // Critical chunks (upper-case first letter: IHDR, PLTE, IDAT, IEND) must be whole; an
    // ancillary one with a bad CRC is dropped by libpng with a warning, as it is here.
    const bool critical = type[0] >= 'A' && type[0] <= 'Z';
    if (critical && expected != static_cast<std::uint32_t>(crc))
      return "its " + type + " chunk at byte " + std::to_string(offset) +
             " fails its CRC (the file is damaged)";
    if (type == "IEND") return std::nullopt;
    offset += 12 + std::uint64_t{length};
  }
}

// An image file as 8-bit BGR (alpha dropped, 16-bit samples by their high byte), empty when it
// cannot be read (`why`, when given, receives the reason where one is known). io::readPng
// refuses a header claiming more pixels than it will decode, e.g. 100000^2.
cv::Mat readImage(const fs::path& file, std::string* why = nullptr) {
  if (const auto problem = pngStructureProblem(file)) {
    if (why) *why = *problem;
    return cv::Mat();
  }
  try {
    Image image = io::readPng(file);
    const cv::Mat rgba(image.height, image.width, CV_8UC4, image.rgba.data());
    cv::Mat bgr;
    cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
    return bgr;
  } catch (const InputError& e) {
    if (why) *why = e.problem();
    return cv::Mat();
  }
}

using detail::fmt;
using nlohmann::json;
using process::kTimedOut;
using process::ProcessJob;
using process::ProcessPool;
using process::ProcessResult;

// One image a render job makes: a case's render (check < 0) or one of its analytic checks.
struct Render {
  std::size_t caseIndex = 0;
  int check = -1;
  std::string view;  // the view's name in the job's study, so its image is out/<view>.png
};

// One render process: some of the renders of one study. A study's renders are spread over at
// most --jobs processes, so the volumes load once per process, not once per case.
struct Job {
  std::vector<Render> renders;
  fs::path study, out, log;
  ProcessResult result;
  json renderJson;  // out/render.json, read once when the process ends
};

// The private folder the job studies and renders live in; removed on every way out.
struct WorkDir {
  fs::path dir;
  WorkDir() : dir(fs::temp_directory_path() / ("mvw-validate-" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~WorkDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// What a failed render said: its last "mvw: " line (its own error message), else its last line
// (a sanitizer's or the runtime's report can follow the message, or replace it).
std::string whatItSaid(const std::string& text) {
  std::istringstream in(text);
  std::string line, own, last;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    last = line;
    if (line.rfind("mvw: ", 0) == 0) own = line;
  }
  return own.empty() ? last : own;
}

// render.json as `mvw render` wrote it; an empty object when it is missing or unreadable.
json readRenderJson(const fs::path& file) {
  try {
    return json::parse(std::ifstream(file));
  } catch (const json::exception&) {
    return json::object();
  }
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

// Everything the suite asks for, checked and turned into render jobs before anything renders.
class Plan {
 public:
  Plan(const Suite& suite, const fs::path& work, int jobsPerStudy, const pacs::Options& pacs)
      : suite_(suite), work_(work), pacs_(pacs) {
    plans_.resize(suite.cases.size());
    for (std::size_t ci = 0; ci < suite.cases.size(); ++ci) addCase(ci);
    makeJobs(std::max(1, jobsPerStudy));
  }

  std::vector<Job> jobs;
  const config::StudyConfig& study(const fs::path& file) const { return studies_.at(file); }
  const Volume& anatomy(const fs::path& studyFile) const {
    return volumes_.at(study(studyFile).anatomical.path);
  }
  const MipPlan& mipPlan(std::size_t ci, int check) const {
    return plans_[ci][static_cast<std::size_t>(check)];
  }

 private:
  struct Wanted {
    Render render;
    config::ViewConfig view;
  };

  [[noreturn]] void bad(const std::string& problem) const {
    throw InputError(suite_.file, problem);
  }

  const config::StudyConfig& loadStudy(const fs::path& file, const std::string& where) {
    if (!studies_.count(file)) {
      try {
        studies_.emplace(file, config::loadStudyConfig(file));
      } catch (const InputError& e) {
        bad(where + ": study config " + e.what());
      }
      studyOrder_.push_back(file);
    }
    return studies_.at(file);
  }

  // `view` checked now (a bad view is the suite's error), named after the case and check.
  void want(std::size_t ci, int check, const fs::path& studyFile, const json& view,
            const std::string& where) {
    const CaseSpec& c = suite_.cases[ci];
    Wanted w;
    w.render.caseIndex = ci;
    w.render.check = check;
    w.render.view =
        "case" + std::to_string(ci) + (check < 0 ? "" : "-check" + std::to_string(check + 1));
    try {
      w.view = config::parseViewConfig(view, studies_.at(studyFile).file, "view", 0);
    } catch (const InputError& e) {
      bad(where + ": view " + (check < 0 ? c.viewLabel : "of check " + std::to_string(check + 1)) +
          ": " + e.problem());
    }
    w.view.name = w.render.view;
    wanted_[studyFile].push_back(std::move(w));
  }

  // Each study's renders dealt round-robin to at most `perStudy` jobs; each job is the study
  // with those views only, written for the render function.
  void makeJobs(int perStudy) {
    for (const fs::path& file : studyOrder_) {
      const std::vector<Wanted>& all = wanted_[file];
      const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(perStudy), all.size());
      for (std::size_t b = 0; b < n; ++b) {
        Job j;
        config::StudyConfig s = studies_.at(file);
        s.render.views.clear();
        for (std::size_t k = b; k < all.size(); k += n) {
          j.renders.push_back(all[k].render);
          s.render.views.push_back(all[k].view);
        }
        const fs::path dir = work_ / ("job" + std::to_string(jobs.size()));
        fs::create_directories(dir);
        j.study = dir / "study.json";
        j.out = dir / "out";
        j.log = dir / "render.log";
        config::writeStudyConfig(s, j.study);
        jobs.push_back(std::move(j));
      }
    }
  }

  // A view of the study by name, as its JSON (so the case renders exactly what the study says).
  json namedView(const config::StudyConfig& study, const std::string& wanted,
                 const fs::path& studyFile, const std::string& where) const {
    std::string known;
    for (const config::ViewConfig& v : study.render.views) {
      known += (known.empty() ? "" : ", ") + v.name;
      if (v.name == wanted) return config::viewConfigJson(v);
    }
    bad(where + ": the study " + studyFile.string() + " has no view named \"" + wanted +
        "\" (it has: " + (known.empty() ? "none" : known) + ")");
  }

  void addCase(std::size_t ci) {
    const CaseSpec& c = suite_.cases[ci];
    const std::string where = "case '" + c.name + "'";
    const config::StudyConfig& study = loadStudy(c.study, where);
    if (c.reference)
      want(
          ci, -1, c.study,
          c.view.is_string() ? namedView(study, c.view.get<std::string>(), c.study, where) : c.view,
          where);
    for (std::size_t k = 0; k < c.checks.size(); ++k) {
      const fs::path& anatomical = study.anatomical.path;
      if (!volumes_.count(anatomical))
        volumes_.emplace(anatomical, study::readAnatomical(study.anatomical, {}, pacs_));
      plans_[ci].push_back(planMip(volumes_.at(anatomical), c.checks[k], suite_.file,
                                   where + " check " + std::to_string(k + 1)));
      want(ci, static_cast<int>(k), c.study, plans_[ci].back().view, where);
    }
  }

  const Suite& suite_;
  fs::path work_;
  const pacs::Options& pacs_;
  std::map<fs::path, config::StudyConfig> studies_;
  std::vector<fs::path> studyOrder_;  // as the suite first names them
  std::map<fs::path, std::vector<Wanted>> wanted_;
  std::map<fs::path, Volume> volumes_;
  std::vector<std::vector<MipPlan>> plans_;
};

// The judgement of one case once all its renders have ended; copies what the report shows.
class CaseJudge {
 public:
  // manifest: the goldens' checksums (null: none); updated: the manifest --update writes.
  CaseJudge(const ValidateOptions& o, const Suite& suite, const Plan& plan, json& environment,
            const ChecksumManifest* manifest, ChecksumManifest* updated)
      : o_(o),
        suite_(suite),
        plan_(plan),
        environment_(environment),
        manifest_(manifest),
        updated_(updated) {}

  CaseResult judge(std::size_t ci, const fs::path& dir) {
    CaseResult r;
    fs::create_directories(dir);
    for (const Job& j : plan_.jobs)
      for (const Render& one : j.renders)
        if (one.caseIndex == ci) judgeRender(r, j, one, dir);
    return r;
  }

 private:
  void judgeRender(CaseResult& r, const Job& j, const Render& one, const fs::path& dir) {
    const std::size_t ci = one.caseIndex;
    const std::string tag = one.check < 0 ? "" : "check" + std::to_string(one.check + 1) + "-";
    io::copyFileAtomically(j.log, dir / (tag + "render.log"));
    const fs::path png = j.out / (one.view + ".png");
    if (j.result.status != 0 || !fs::exists(png)) {
      renderFailed(r, j, one);
      return;
    }
    noteEnvironment(j.renderJson);
    r.renderMs += renderMsOf(j.renderJson, one.view);
    const cv::Mat rendered = readImage(png);
    if (rendered.empty()) {
      r.pass = false;
      r.problems.push_back("the render " + png.string() + " cannot be read");
      return;
    }
    if (one.check >= 0)
      judgeCheck(r, ci, one.check, png, rendered, dir, tag);
    else
      judgeImage(r, suite_.cases[ci], rendered, png, dir, glOf(j.renderJson));
  }

  void renderFailed(CaseResult& r, const Job& j, const Render& one) const {
    r.pass = false;
    const std::string why =
        j.result.status == kTimedOut ? "timed out after " + fmt(o_.timeoutS, 0) + " s"
        : j.result.status != 0       ? "mvw render exited with " + std::to_string(j.result.status)
                                     : "mvw render wrote no " + one.view + ".png";
    r.problems.push_back(
        (one.check < 0 ? "render: " : "check " + std::to_string(one.check + 1) + " render: ") +
        why + ": " + whatItSaid(readText(j.log)));
    if (one.check >= 0) r.checks.push_back(CheckResult{false, "not rendered", 0, 0, 0, 0});
  }

  void noteEnvironment(const json& rj) {
    if (!environment_["gl_renderer"].is_null() || !rj.is_object()) return;
    environment_["gl_backend"] = rj.value("gl_backend", "");
    environment_["gl_renderer"] = rj.value("gl_renderer", "");
    environment_["gl_version"] = rj.value("gl_version", "");
    environment_["mvw_version"] = rj.value("mvw_version", "");
  }

  // The milliseconds `mvw render` took for one view (render.json's ms_per_frame).
  static double renderMsOf(const json& rj, const std::string& view) {
    if (!rj.contains("views") || !rj["views"].is_array()) return 0.0;
    for (const json& v : rj["views"])
      if (v.is_object() && v.value("file", "") == view + ".png")
        return v.value("ms_per_frame", 0.0);
    return 0.0;
  }

  // The GL renderer and version string a render was made with (render.json).
  static std::pair<std::string, std::string> glOf(const json& rj) {
    if (!rj.is_object()) return {};
    return {rj.value("gl_renderer", ""), rj.value("gl_version", "")};
  }

  void judgeCheck(CaseResult& r, std::size_t ci, int check, const fs::path& png,
                  const cv::Mat& rendered, const fs::path& dir, const std::string& tag) const {
    const CaseSpec& c = suite_.cases[ci];
    const CheckSpec& spec = c.checks[static_cast<std::size_t>(check)];
    cv::Mat expected, heat;
    CheckResult cr = evaluateMip(plan_.anatomy(c.study), spec, plan_.mipPlan(ci, check), rendered,
                                 expected, heat);
    writeMatPng(expected, dir / (tag + "expected.png"));
    io::copyFileAtomically(png, dir / (tag + "render.png"));
    writeMatPng(heat, dir / (tag + "diff.png"));
    if (!cr.pass) {
      r.pass = false;
      r.problems.push_back("check " + std::to_string(check + 1) + ": " + cr.message);
    }
    r.checks.push_back(cr);
  }

  void judgeImage(CaseResult& r, const CaseSpec& c, const cv::Mat& rendered, const fs::path& png,
                  const fs::path& dir, const std::pair<std::string, std::string>& gl) const {
    io::copyFileAtomically(png, dir / "render.png");
    r.hasRender = true;
    const fs::path& ref = *c.reference;
    const bool refExists = fs::exists(ref);
    cv::Mat reference;
    std::string unreadable;
    if (refExists) reference = readImage(ref, &unreadable);
    if (refExists && !reference.empty() && reference.size() == rendered.size()) {
      r.metrics = compareImages(rendered, reference, c.tolerance.maxDelta);
      writeMatPng(r.metrics->heat, dir / "diff.png");
      r.hasDiff = true;
    }
    const bool exact = manifest_ && manifest_->exactOn(gl.first, gl.second);
    if (!o_.update) r.comparison = exact ? "exact" : "tolerance only";
    if (o_.update) {
      r.updateNote = updateNote(r, reference, rendered, refExists);
      if (updated_) updated_->images[updated_->keyOf(ref)] = pixelSha256(rendered);
      fs::create_directories(ref.parent_path());
      io::copyFileAtomically(png, ref);
      r.updated = true;
      io::copyFileAtomically(png, dir / "reference.png");
      r.hasReference = true;
      return;
    }
    if (!refExists) {
      r.pass = false;
      r.problems.push_back("reference " + ref.string() + " is missing (--update writes it)");
      return;
    }
    if (reference.empty()) {
      r.pass = false;
      r.problems.push_back("reference " + ref.string() + " is not a readable image" +
                           (unreadable.empty() ? "" : ": " + unreadable));
      return;
    }
    io::copyFileAtomically(ref, dir / "reference.png");
    r.hasReference = true;
    if (reference.size() != rendered.size()) {
      r.pass = false;
      r.problems.push_back("size " + std::to_string(rendered.cols) + " x " +
                           std::to_string(rendered.rows) + " differs from the reference's " +
                           std::to_string(reference.cols) + " x " + std::to_string(reference.rows));
      return;
    }
    judgeTolerance(r, *r.metrics, c.tolerance);
    if (exact) judgeChecksum(r, ref, reference, rendered, gl.first);
  }

  // Old reference against the new render, printed by --update before a commit carries it.
  static std::string updateNote(const CaseResult& r, const cv::Mat& reference,
                                const cv::Mat& rendered, bool refExists) {
    if (!refExists || reference.empty()) return "new reference";
    if (reference.size() != rendered.size())
      return "old vs new: size " + std::to_string(reference.cols) + " x " +
             std::to_string(reference.rows) + " -> " + std::to_string(rendered.cols) + " x " +
             std::to_string(rendered.rows);
    const Metrics& m = *r.metrics;
    if (m.maxDelta == 0) return "unchanged (old and new pixels are identical)";
    return "old vs new: PSNR " + fmt(m.psnr, 2) + " dB, SSIM " + fmt(m.ssim, 4) +
           ", mean abs delta " + fmt(m.meanDelta, 3) + "/255, max abs delta " + fmt(m.maxDelta, 0) +
           "/255";
  }

  // On the goldens' own renderer the render must be bit-identical: its pixels, and the
  // reference's, must hash to the manifest's checksum.
  void judgeChecksum(CaseResult& r, const fs::path& ref, const cv::Mat& reference,
                     const cv::Mat& rendered, const std::string& renderer) const {
    const auto it = manifest_->images.find(manifest_->keyOf(ref));
    if (it == manifest_->images.end()) {
      r.problems.push_back("exact: " + manifest_->file.string() + " has no checksum for " +
                           manifest_->keyOf(ref) + " (--update writes it)");
    } else if (pixelSha256(reference) != it->second) {
      r.problems.push_back("exact: the reference " + ref.string() +
                           " does not match its checksum in " + manifest_->file.string() +
                           " (changed without --update?)");
    } else {
      const std::string got = pixelSha256(rendered);
      if (got != it->second)
        r.problems.push_back("exact: the render's pixel SHA-256 " + got.substr(0, 16) +
                             "... differs from the golden's " + it->second.substr(0, 16) +
                             "... (on " + renderer +
                             ", the goldens' renderer, renders are "
                             "bit-identical)");
    }
    if (!r.problems.empty()) r.pass = false;
  }

  static void judgeTolerance(CaseResult& r, const Metrics& m, const Tolerance& t) {
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

  const ValidateOptions& o_;
  const Suite& suite_;
  const Plan& plan_;
  json& environment_;
  const ChecksumManifest* manifest_;
  ChecksumManifest* updated_;
};

}  // namespace

bool runValidate(const ValidateOptions& o) {
  const Suite suite = loadSuite(o.suite);
  // The goldens' checksums, read before anything renders (a bad manifest is bad input).
  std::optional<ChecksumManifest> manifest, updated;
  if (suite.checksums) {
    if (!o.update || fs::exists(*suite.checksums))
      manifest = loadChecksumManifest(*suite.checksums);
    if (o.update) {
      updated.emplace();
      updated->file = *suite.checksums;
    }
  }
  // The render processes are forked from a launcher forked now, before this process reads a
  // volume (VTK) or judges an image (OpenCV): both start TBB worker threads, whose state a
  // child forked from this process later would hold half-copied.
  ProcessPool pool([gl = o.gl, pacs = o.pacs](const std::vector<std::string>& args) {
    output::RenderRequest request;
    request.study = args.at(0);
    request.outDir = args.at(1);
    request.gl = gl;
    request.pacs = pacs;
    output::renderStudy(request, std::cout, std::cerr);
    return 0;
  });
  const WorkDir work;
  Plan plan(suite, work.dir, o.jobs, o.pacs);

  const fs::path report = o.outDir;
  {
    std::error_code ec;
    fs::create_directories(report / "cases", ec);
    if (ec) throw InputError(report, "cannot create the report folder: " + ec.message());
  }
  std::vector<ProcessJob> processes;
  for (const Job& j : plan.jobs) processes.push_back({{j.study.string(), j.out.string()}, j.log});
  std::vector<int> pending(suite.cases.size(), 0);
  for (const Job& j : plan.jobs)
    for (const Render& one : j.renders) ++pending[one.caseIndex];

  const bool tty = ::isatty(STDERR_FILENO) != 0;
  json environment = {{"mvw_version", nullptr},
                      {"gl_backend", nullptr},
                      {"gl_renderer", nullptr},
                      {"gl_version", nullptr}};
  std::vector<CaseResult> results(suite.cases.size());
  CaseJudge judge(o, suite, plan, environment, manifest ? &*manifest : nullptr,
                  updated ? &*updated : nullptr);
  std::size_t casesDone = 0;
  progressBar(0, suite.cases.size(), tty);
  pool.run(processes, o.jobs, o.timeoutS, [&](std::size_t job, const ProcessResult& result) {
    plan.jobs[job].result = result;
    plan.jobs[job].renderJson = readRenderJson(plan.jobs[job].out / "render.json");
    for (const Render& one : plan.jobs[job].renders) {
      const std::size_t ci = one.caseIndex;
      if (--pending[ci] != 0) continue;
      results[ci] = judge.judge(ci, report / "cases" / suite.cases[ci].name);
      ++casesDone;
      if (tty) std::cerr << "\r\033[K";
      std::cout << caseLine(suite.cases[ci], results[ci]) << std::endl;
      progressBar(casesDone, suite.cases.size(), tty);
    }
  });
  if (tty) std::cerr << "\n";

  environment["host"] = hostName();
  environment["date_utc"] = utcNow();
  environment["jobs"] = o.jobs;
  const auto envText = [&](const char* key) {
    return environment[key].is_string() ? environment[key].get<std::string>() : std::string("?");
  };
  std::string comparison = "tolerance only (the suite has no checksums)";
  if (updated) {
    updated->glRenderer = envText("gl_renderer");
    updated->glVersion = envText("gl_version");
    writeChecksumManifest(*updated);
    comparison = "checksums written for " + updated->glRenderer;
  } else if (manifest && manifest->exactOn(envText("gl_renderer"), envText("gl_version"))) {
    comparison =
        "exact (pixel SHA-256) and by tolerance, on the goldens' renderer " + manifest->glRenderer;
  } else if (manifest) {
    comparison = "tolerance only: GL renderer " + envText("gl_renderer") + " / " +
                 envText("gl_version") + " is not the goldens' " + manifest->glRenderer + " / " +
                 manifest->glVersion;
  }
  environment["comparison"] = comparison;
  writeReport(suite, results, environment, o.update, report);
  int passed = 0;
  for (const auto& r : results) passed += r.pass ? 1 : 0;
  const bool allPass = passed == static_cast<int>(results.size());
  std::cout << (allPass ? "passed: " : "FAILED: ") << passed << " of " << results.size()
            << " cases pass" << (o.update ? " (references updated)" : "") << "; GL "
            << (environment["gl_backend"].is_string() ? environment["gl_backend"].get<std::string>()
                                                      : std::string("?"))
            << "; compared " << comparison << "; report " << (report / "index.html").string()
            << std::endl;
  return allPass;
}

}  // namespace mvw::validate
