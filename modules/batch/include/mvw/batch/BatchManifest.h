#pragma once
// A cohort manifest for `mvw batch`: one line per study, its id, its study config and the work
// to do (render, stats or register), with more columns for the command's options. CSV with the
// header `id,study,task` (then option columns, named as the option without its dashes), or the
// same as JSON (`{"studies": [{"id": ..., "study": ..., "task": ..., "options": {...}}]}`).
// Every bad row is refused on load, naming the file and the line: nothing runs from a manifest
// that is wrong anywhere.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mvw::batch {

// How a task's command takes one option: a flag takes no value (`true` in the manifest), any
// other option 1 to maxValues values.
struct TaskOption {
  bool flag = false;
  int maxValues = 1;
};

// The options each task's command takes (`mvw render --help`...), by task, then by long name
// without its dashes. The app reads them from the commands' own command lines, their one
// definition.
using TaskOptions = std::map<std::string, std::map<std::string, TaskOption>>;

struct BatchStudy {
  std::string id;                                            // also its output folder's name
  std::filesystem::path study;                               // the study config, absolute
  std::string task;                                          // render | stats | register
  std::vector<std::pair<std::string, std::string>> options;  // option name -> value ("" = flag)
  std::string studyText;                                     // the study column as written
  std::string line;    // the manifest line as written (its JSON object for JSON)
  int lineNumber = 0;  // 1-based; the object's index + 1 for JSON
};

struct BatchManifest {
  std::filesystem::path file;
  std::vector<BatchStudy> studies;  // in manifest order
};

// Throws InputError naming the file and the line for: a missing or unreadable file, a wrong
// header, a row with the wrong number of fields, an empty or unusable id, a duplicate id, an
// unknown task, a study config that does not exist, a bad option column name. With `known`,
// also for an option its line gives that the line's task does not take, `true` for an option
// that takes values, a value for a flag, more values than the option takes, and a value that
// is itself an option ("--mode"): a study is never started to fail on its command line. An
// empty `known` checks only the names' form (the file format's own tests and fuzzing).
BatchManifest loadBatchManifest(const std::filesystem::path& file, const TaskOptions& known = {});

// The tasks a manifest may name.
const std::vector<std::string>& batchTasks();

}  // namespace mvw::batch
