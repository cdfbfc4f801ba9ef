#include "mvw/batch/BatchSlurm.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "mvw/io/AtomicFile.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

// Single quotes for the shell: nothing inside them is expanded.
std::string quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Where sbatch sends the job: SlurmctldHost (and SlurmctldPort) of the slurm.conf it reads.
std::string controller() {
  const char* env = std::getenv("SLURM_CONF");
  const fs::path conf = env && *env ? fs::path(env) : fs::path("/etc/slurm/slurm.conf");
  std::ifstream in(conf);
  std::string line, host, port;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if ((key == "SlurmctldHost" || key == "ControlMachine") && host.empty()) host = value;
    if (key == "SlurmctldPort") port = value;
  }
  if (host.empty()) return "the Slurm controller of " + conf.string();
  return "the Slurm controller " + host + (port.empty() ? "" : ":" + port) + " (" + conf.string() +
         ")";
}

}  // namespace

int parseMaxArraySize(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key, eq, value;
    if (words >> key >> eq >> value && key == "MaxArraySize" && eq == "=" &&
        value.find_first_not_of("0123456789") == std::string::npos && value.size() < 10)
      return std::stoi(value);
  }
  return 0;
}

int slurmMaxArraySize() {
  FILE* pipe = ::popen("scontrol show config 2>/dev/null", "r");
  if (!pipe) return 0;
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = ::pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return 0;
  return parseMaxArraySize(output);
}

void checkSlurmArraySize(int tasks, int maxArraySize) {
  if (maxArraySize <= 0 || tasks <= maxArraySize) return;
  throw InputError("--tasks " + std::to_string(tasks),
                   "is more than one Slurm array may hold on " + controller() +
                       ": its MaxArraySize is " + std::to_string(maxArraySize) + " (task ids 0-" +
                       std::to_string(maxArraySize - 1) + "); give --tasks " +
                       std::to_string(maxArraySize) +
                       " or fewer (each task runs a shard of the manifest, so fewer tasks still "
                       "cover every study)");
}

std::string slurmScript(const SlurmJobOptions& o) {
  const fs::path out = fs::absolute(o.out).lexically_normal();
  const fs::path manifest = fs::absolute(o.manifest).lexically_normal();
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by mvw batch slurm: " << o.tasks
    << " array tasks, each one shard of the manifest.\n"
    << "# Resubmitting it is safe: studies already done are skipped.\n"
    << "#SBATCH --job-name=mvw-batch\n"
    << "#SBATCH --array=0-" << (o.tasks - 1);
  if (o.throttle > 0) s << "%" << o.throttle;
  s << "\n"
    << "#SBATCH --output=" << (out / "logs" / "task-%A_%a.log").string() << "\n"
    << "#SBATCH --cpus-per-task=" << o.jobs << "\n";
  if (!o.partition.empty()) s << "#SBATCH --partition=" << o.partition << "\n";
  if (!o.time.empty()) s << "#SBATCH --time=" << o.time << "\n";
  if (!o.mem.empty()) s << "#SBATCH --mem=" << o.mem << "\n";
  s << "set -eu\n"
    << "exec " << quote(fs::absolute(o.mvwExecutable).string()) << " batch run "
    << quote(manifest.string()) << " -o " << quote(out.string())
    << " --shard \"${SLURM_ARRAY_TASK_ID}/" << o.tasks << "\" --jobs " << o.jobs;
  for (const std::string& option : o.mvwOptions) s << " " << quote(option);
  s << "\n";
  return s.str();
}

fs::path writeSlurmScript(const SlurmJobOptions& o) {
  std::error_code ec;
  fs::create_directories(o.out / "logs", ec);
  if (ec) throw InputError(o.out, "cannot be made as the output folder: " + ec.message());
  const fs::path script = o.out / "batch.sbatch";
  io::writeTextAtomically(script, slurmScript(o));
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  return script;
}

std::string submitSlurmScript(const fs::path& script) {
  const std::string command = "sbatch --parsable " + quote(script.string()) + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw Error("sbatch cannot be started");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = ::pclose(pipe);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
  if (code == 127)
    throw InputError("sbatch", "is not installed here (the Slurm client, Debian's slurm-client)");
  if (code != 0) {
    const std::string last =
        output.substr(output.rfind('\n') == std::string::npos ? 0 : output.rfind('\n') + 1);
    throw SchedulerError("sbatch could not submit " + script.string() + " to " + controller() +
                         ": " + (last.empty() ? "exit " + std::to_string(code) : last));
  }
  // --parsable prints "jobid" or "jobid;cluster".
  std::string id =
      output.substr(output.rfind('\n') == std::string::npos ? 0 : output.rfind('\n') + 1);
  if (const auto semi = id.find(';'); semi != std::string::npos) id = id.substr(0, semi);
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw SchedulerError("sbatch answered '" + output + "' from " + controller() +
                         ", not a job id");
  return id;
}

}  // namespace mvw::batch
