#include "mvw/batch/BatchRecord.h"

#include <ctime>

#include "mvw/io/AtomicFile.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// What done.json and failed.json share: the study, its command and inputs, mvw's version.
nlohmann::json sharedRecord(const StudyRun& run, const RecordContext& context, const char* status,
                            double seconds) {
  nlohmann::json j;
  j["id"] = run.study->id;
  j["status"] = status;
  j["task"] = run.study->task;
  j["seconds"] = seconds;
  j["command"] = run.command;
  j["manifest"] = context.manifest.string();
  j["manifest_line"] = run.study->line;
  j["inputs"] = run.inputs;
  j["mvw_version"] = context.version;
  j["finished_utc"] = utcNow();
  return j;
}

}  // namespace

nlohmann::json failedRecord(const StudyRun& run, const RecordContext& context, int exitCode,
                            const std::string& message, double seconds) {
  nlohmann::json j = sharedRecord(run, context, "failed", seconds);
  j["exit_code"] = exitCode;
  j["message"] = message;
  return j;
}

nlohmann::json doneRecord(const StudyRun& run, const RecordContext& context, double seconds) {
  nlohmann::json j = sharedRecord(run, context, "done", seconds);
  nlohmann::json outputs = nlohmann::json::object();
  for (const auto& e : fs::recursive_directory_iterator(run.work))
    if (e.is_regular_file() && e.path().filename() != "log.txt")
      outputs[e.path().lexically_relative(run.work).generic_string()] =
          process::fileSha256(e.path(), "an input of a batch study");
  j["outputs"] = outputs;
  return j;
}

void writeRecord(const fs::path& file, const nlohmann::json& record) {
  io::writeTextAtomically(file, record.dump(2) + "\n");
}

}  // namespace mvw::batch
