#include "mvw/validate/BatchRun.h"

#include <fcntl.h>
#include <openssl/evp.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "JsonFile.h"
#include "Sha256.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/ExitCode.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/validate/BatchReport.h"
#include "mvw/validate/ProcessPool.h"

namespace mvw::validate {

namespace fs = std::filesystem;

namespace {

void hashFileInto(EVP_MD_CTX* ctx, const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot be read (an input of a batch study)");
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    EVP_DigestUpdate(ctx, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(file, "cannot be read (an input of a batch study)");
}

// A folder (a DICOM series) hashes as the names and bytes of its files, in name order.
std::string pathSha256(const fs::path& path) {
  detail::Sha256 ctx = detail::newSha256();
  if (fs::is_directory(path)) {
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(path))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const std::string name = f.lexically_relative(path).generic_string();
      EVP_DigestUpdate(ctx.get(), name.data(), name.size() + 1);
      hashFileInto(ctx.get(), f);
    }
  } else {
    hashFileInto(ctx.get(), path);
  }
  return detail::hexDigest(ctx);
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// The last line a failed command said ("mvw: error: ..."), for the report.
std::string lastMessage(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last, lastError;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    last = line;
    if (line.rfind("mvw: ", 0) == 0) lastError = line;
  }
  std::string message = lastError.empty() ? last : lastError;
  if (message.size() > 2000) message = message.substr(0, 2000) + "...";
  return message;
}

// Deletes what a killed run of this study left: OUT/.work-<id>-* and OUT/.old-<id>-*. Shards
// are disjoint, so no other live task works on this id.
void removeLeftovers(const fs::path& out, const std::string& id) {
  std::vector<fs::path> stale;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    for (const char* prefix : {".work-", ".old-"}) {
      const std::string p = std::string(prefix) + id + "-";
      if (name.rfind(p, 0) == 0 && name.find('-', p.size()) == std::string::npos)
        stale.push_back(e.path());
    }
  }
  for (const auto& p : stale) fs::remove_all(p);
}

// Moves the finished work folder into OUT/<id>. The old result steps aside first, so no moment
// has a done.json in OUT/<id> that is not this run's or the last complete run's.
void publish(const fs::path& work, const fs::path& out, const std::string& id) {
  const fs::path target = out / id;
  const fs::path old = out / (".old-" + id + "-" + std::to_string(::getpid()));
  if (fs::exists(target)) fs::rename(target, old);
  fs::rename(work, target);
  if (fs::exists(old)) fs::remove_all(old);
  // The renames reach the disk before a later run trusts them.
  const int fd = ::open(out.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace

std::string fileSha256(const fs::path& file) {
  detail::Sha256 ctx = detail::newSha256();
  hashFileInto(ctx.get(), file);
  return detail::hexDigest(ctx);
}

std::map<std::string, std::string> batchInputChecksums(const BatchStudy& study) {
  std::map<std::string, std::string> sums;
  sums[study.study.string()] = fileSha256(study.study);
  std::vector<fs::path> paths;
  if (study.study.extension() == ".json") {
    const config::StudyConfig config = config::loadStudyConfig(study.study);
    paths.push_back(config.anatomical.path);
    if (config.functional) paths.push_back(config.functional->path);
    if (config.segmentation) paths.push_back(config.segmentation->path);
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
    if (!sums.count(abs.string())) sums[abs.string()] = pathSha256(abs);
  }
  return sums;
}

std::vector<std::string> batchCommand(const BatchStudy& study, const fs::path& folder) {
  std::vector<std::string> args{study.task};
  if (study.task == "render") {
    args.insert(args.end(), {study.study.string(), "-o", folder.string()});
  } else if (study.task == "stats") {
    args.insert(args.end(), {study.study.string(), "--json"});
  } else {  // register: the study's anatomical volume is fixed, its functional one moves
    const config::StudyConfig config = config::loadStudyConfig(study.study);
    if (!config.functional)
      throw InputError(study.study,
                       "has no functional volume to register (batch study '" + study.id + "')");
    args.insert(args.end(), {"--fixed", config.anatomical.path.string(), "--moving",
                             config.functional->path.string(), "-o", folder.string()});
    if (!config.anatomical.series.empty())
      args.insert(args.end(), {"--fixed-series", config.anatomical.series});
    if (!config.functional->series.empty())
      args.insert(args.end(), {"--moving-series", config.functional->series});
  }
  for (const auto& [name, value] : study.options) {
    args.push_back("--" + name);
    // A list value ("256 256", "0 0 0 40") is several arguments of one option.
    std::istringstream words(value);
    for (std::string w; words >> w;) args.push_back(w);
  }
  return args;
}

BatchRunCounts runBatch(const BatchManifest& manifest, const BatchRunOptions& options,
                        std::ostream& progress) {
  const fs::path out = fs::absolute(options.out).lexically_normal();
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out))
    throw InputError(options.out, "cannot be made as the output folder: " + ec.message());
  if (::access(out.c_str(), W_OK) != 0) throw InputError(options.out, "is not writable");
  std::vector<std::string> ids;
  for (const auto& s : manifest.studies) ids.push_back(s.id);
  writeBatchIndex(out, manifest.file, ids);

  // The pool forks its launcher now, before anything starts threads.
  const std::string exe = options.mvwExecutable.string();
  ProcessPool pool([exe](const std::vector<std::string>& args) {
    // args[0]: where stdout goes ("" = the log); the rest: mvw's arguments.
    if (!args[0].empty()) {
      const int fd = ::open(args[0].c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0 || ::dup2(fd, 1) < 0) {
        std::cerr << "mvw: error: " << args[0] << ": cannot be written\n";
        return 1;
      }
      ::close(fd);
    }
    std::vector<char*> argv{const_cast<char*>(exe.c_str())};
    for (std::size_t i = 1; i < args.size(); ++i)
      argv.push_back(const_cast<char*>(args[i].c_str()));
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    std::cerr << "mvw: error: " << exe << " cannot be started: " << std::strerror(errno) << "\n";
    return 127;
  });

  BatchRunCounts counts;
  struct Pending {
    const BatchStudy* study;
    fs::path work;
    std::map<std::string, std::string> inputs;
    std::vector<std::string> command;
  };
  std::vector<Pending> pending;
  std::vector<ProcessJob> jobs;
  std::vector<const BatchStudy*> mine;
  for (std::size_t i = 0; i < manifest.studies.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(options.shard.count)) == options.shard.index)
      mine.push_back(&manifest.studies[i]);
  counts.total = static_cast<int>(mine.size());

  auto line = [&](const std::string& id, const std::string& what) {
    const int left = counts.total - counts.done - counts.skipped - counts.failed;
    progress << "[" << (counts.done + counts.skipped) << " done, " << counts.failed << " failed, "
             << left << " left] " << id << ": " << what << std::endl;
  };
  // What done.json and failed.json share: the study, its command and inputs, mvw's version.
  auto record = [&](const Pending& p, const char* status, double seconds) {
    nlohmann::json j;
    j["id"] = p.study->id;
    j["status"] = status;
    j["task"] = p.study->task;
    j["seconds"] = seconds;
    j["command"] = p.command;
    j["manifest"] = manifest.file.string();
    j["manifest_line"] = p.study->line;
    j["inputs"] = p.inputs;
    j["mvw_version"] = options.version;
    j["finished_utc"] = utcNow();
    return j;
  };
  auto recordFailure = [&](const Pending& p, int status, const std::string& message,
                           double seconds) {
    nlohmann::json j = record(p, "failed", seconds);
    j["exit_code"] = status;
    j["message"] = message;
    io::writeTextAtomically(p.work / "failed.json", j.dump(2) + "\n");
    publish(p.work, out, p.study->id);
    ++counts.failed;
    line(p.study->id, "failed (exit " + std::to_string(status) + "): " + message);
  };

  for (const BatchStudy* study : mine) {
    removeLeftovers(out, study->id);
    Pending p{study, out / (".work-" + study->id + "-" + std::to_string(::getpid())), {}, {}};
    fs::create_directories(p.work);
    // A study whose inputs cannot be read fails as its process would: the same code and message.
    std::ostringstream problem;
    const int status = runReportingErrors(
        [&] {
          p.inputs = batchInputChecksums(*study);
          p.command = batchCommand(*study, p.work);
          return kExitSuccess;
        },
        problem);
    if (status != kExitSuccess) {
      std::string message = problem.str();
      if (!message.empty() && message.back() == '\n') message.pop_back();
      recordFailure(p, status, message, 0.0);
      continue;
    }
    const nlohmann::json done = detail::readJsonOrNull(out / study->id / "done.json");
    if (done.is_object() && done.value("manifest_line", "") == study->line &&
        done.contains("inputs") && done["inputs"] == nlohmann::json(p.inputs)) {
      fs::remove_all(p.work);
      ++counts.skipped;
      line(study->id, "done before, skipped");
      continue;
    }
    jobs.push_back(
        {{study->task == "stats" ? (p.work / "stats.json").string() : ""}, p.work / "log.txt"});
    jobs.back().args.insert(jobs.back().args.end(), p.command.begin(), p.command.end());
    pending.push_back(std::move(p));
  }

  pool.run(
      jobs, std::max(1, options.jobs), options.timeoutS,
      [&](std::size_t k, const ProcessResult& result) {
        Pending& p = pending[k];
        if (result.status != 0) {
          std::string message = lastMessage(p.work / "log.txt");
          if (result.status == kTimedOut)
            message = "killed after " + std::to_string(static_cast<int>(options.timeoutS)) +
                      " s (the time limit); " + message;
          else if (result.status > 128)
            message = "killed by signal " + std::to_string(result.status - 128) + "; " + message;
          recordFailure(p, result.status, message, result.seconds);
          return;
        }
        nlohmann::json j = record(p, "done", result.seconds);
        nlohmann::json outputs = nlohmann::json::object();
        for (const auto& e : fs::recursive_directory_iterator(p.work))
          if (e.is_regular_file() && e.path().filename() != "log.txt")
            outputs[e.path().lexically_relative(p.work).generic_string()] = fileSha256(e.path());
        j["outputs"] = outputs;
        // done.json is the last file written: it exists only beside complete outputs.
        io::writeTextAtomically(p.work / "done.json", j.dump(2) + "\n");
        publish(p.work, out, p.study->id);
        ++counts.done;
        char secs[32];
        std::snprintf(secs, sizeof secs, "%.1f", result.seconds);
        line(p.study->id, std::string("done (") + secs + " s)");
      });
  progress << "batch: " << counts.done << " done now, " << counts.skipped << " done before, "
           << counts.failed << " failed, of " << counts.total << " in shard " << options.shard.index
           << "/" << options.shard.count << std::endl;
  return counts;
}

}  // namespace mvw::validate
