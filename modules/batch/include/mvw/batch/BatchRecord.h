#pragma once
// The markers a batch study's run leaves in its folder: done.json (the inputs' checksums, the
// manifest line, mvw's version, the outputs' checksums), the last file written, so it exists
// only beside complete outputs; or failed.json (the exit code and the message). The report and
// the next run's skip-or-rerun decision read them.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvw/batch/BatchManifest.h"

namespace mvw::batch {

// One study's run: its work folder, the checksums of its inputs and its command line.
struct StudyRun {
  const BatchStudy* study = nullptr;
  std::filesystem::path work;
  std::map<std::string, std::string> inputs;
  std::vector<std::string> command;
};

// What every marker of one `mvw batch run` records beside the study.
struct RecordContext {
  std::filesystem::path manifest;
  std::string version;  // mvw's
};

// failed.json: the shared fields (id, status "failed", task, seconds, command, manifest,
// manifest_line, inputs, mvw_version, finished_utc), the exit code and the message.
nlohmann::json failedRecord(const StudyRun& run, const RecordContext& context, int exitCode,
                            const std::string& message, double seconds);

// done.json: the shared fields with status "done" and "outputs", the SHA-256 of every file in
// the work folder but log.txt, keyed by its path relative to the folder.
nlohmann::json doneRecord(const StudyRun& run, const RecordContext& context, double seconds);

// Written atomically, indented by 2, with a final newline.
void writeRecord(const std::filesystem::path& file, const nlohmann::json& record);

}  // namespace mvw::batch
