#pragma once
// `mvw validate`: every case of a suite rendered headless as `mvw render` renders it
// (in child processes, N at a time; the renders of one study are dealt to at most N of them),
// compared with its reference under the case's tolerances, its analytic checks run, and the
// report written. See app/ValidateCommand.h for the format.
#include <filesystem>
#include <string>

#include "mvw/pacs/Pacs.h"

namespace mvw::validate {

struct ValidateOptions {
  std::filesystem::path suite;
  std::filesystem::path outDir;
  bool update = false;  // rewrite the references with the new renders
  int jobs = 1;
  double timeoutS = 600.0;  // per render process
  // --gl for every render (empty: MVW_GL, else auto). Each render process runs `mvw render
  // STUDY -o OUT --gl GL`'s code (output::renderStudy) in a child forked for it (see
  // mvw/process/ProcessPool.h): its output goes to the process's render.log, an exception fails the
  // cases it was to render (exit 2 for InputError, 1 otherwise, its message in the report), and a
  // crash or a hang past timeoutS fails them too, not the run.
  std::string gl;
  // How the studies' PACS series are retrieved (--cache and the time-outs), by this process
  // (the anatomy of an analytic check) and by every render process.
  pacs::Options pacs;
};

// True when every case passes. Throws InputError (naming the suite or a study) for a bad
// suite, before anything renders. Forks a process launcher as it starts (ProcessPool): call it
// before starting threads.
bool runValidate(const ValidateOptions& options);

}  // namespace mvw::validate
