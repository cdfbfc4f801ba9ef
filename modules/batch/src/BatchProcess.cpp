#include "mvw/batch/BatchProcess.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

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

}  // namespace

std::vector<std::string> batchCommand(const BatchStudy& study, const fs::path& folder,
                                      const std::vector<std::string>& mvwOptions) {
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
    if (!config.anatomical.pacs.empty() || !config.functional->pacs.empty()) {
      // A PACS series has no path to name: mvw register reads the config's series itself.
      args.insert(args.end(), {study.study.string(), "-o", folder.string()});
    } else {
      args.insert(args.end(), {"--fixed", config.anatomical.path.string(), "--moving",
                               config.functional->path.string(), "-o", folder.string()});
      if (!config.anatomical.series.empty())
        args.insert(args.end(), {"--fixed-series", config.anatomical.series});
      if (!config.functional->series.empty())
        args.insert(args.end(), {"--moving-series", config.functional->series});
    }
  }
  for (const auto& [name, value] : study.options) {
    args.push_back("--" + name);
    // A list value ("256 256", "0 0 0 40") is several arguments of one option.
    std::istringstream words(value);
    for (std::string w; words >> w;) args.push_back(w);
  }
  args.insert(args.end(), mvwOptions.begin(), mvwOptions.end());
  return args;
}

std::vector<std::string> batchCommandOrPlain(const BatchStudy& study, const fs::path& folder,
                                             const std::vector<std::string>& mvwOptions) {
  try {
    return batchCommand(study, folder, mvwOptions);
  } catch (const std::exception&) {
    std::vector<std::string> args{study.task, study.study.string()};
    if (study.task != "stats") args.insert(args.end(), {"-o", folder.string()});
    args.insert(args.end(), mvwOptions.begin(), mvwOptions.end());
    return args;
  }
}

process::ProcessJob batchJob(const BatchStudy& study, const fs::path& work,
                             const std::vector<std::string>& command) {
  process::ProcessJob job{{study.task == "stats" ? (work / "stats.json").string() : ""},
                          work / "log.txt"};
  job.args.insert(job.args.end(), command.begin(), command.end());
  return job;
}

process::JobFunction mvwJobFunction(const fs::path& executable) {
  return [exe = executable.string()](const std::vector<std::string>& args) {
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
  };
}

void discardFailedOutput(const BatchStudy& study, const fs::path& work) {
  std::error_code ec;
  if (study.task == "stats") fs::remove(work / "stats.json", ec);
}

std::string batchFailureMessage(const process::ProcessResult& result, const fs::path& log,
                                double timeoutS) {
  std::string message = lastMessage(log);
  if (result.status == process::kTimedOut)
    message = "killed after " + std::to_string(static_cast<int>(timeoutS)) +
              " s (the time limit); " + message;
  else if (result.status > 128)
    message = "killed by signal " + std::to_string(result.status - 128) + "; " + message;
  return message;
}

fs::path selfExecutable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot find mvw's own executable (/proc/self/exe): " + ec.message());
  return self;
}

}  // namespace mvw::batch
