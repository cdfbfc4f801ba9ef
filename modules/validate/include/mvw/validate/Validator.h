#pragma once
// `mvw validate`: every case of a suite rendered headless by the caller's render function
// (in child processes, N at a time; the renders of one study are dealt to at most N of them),
// compared with its reference under the case's tolerances, its analytic checks run, and the
// report written. See app/ValidateCommand.h for the format.
#include <filesystem>
#include <functional>

namespace mvw::validate {

// Renders every view of the study config `study` into the folder `outDir`, as `mvw render
// STUDY -o OUT_DIR` does: <view name>.png for each view and render.json (the GL backend,
// renderer and version, and each view's ms_per_frame, which the report shows). Throws
// InputError for bad input, another exception for an internal fault.
using RenderStudy =
    std::function<void(const std::filesystem::path& study, const std::filesystem::path& outDir)>;

struct ValidateOptions {
  std::filesystem::path suite;
  std::filesystem::path outDir;
  bool update = false;  // rewrite the references with the new renders
  int jobs = 1;
  double timeoutS = 600.0;  // per render process
  // Called once per render process, in a child forked for it (see ProcessPool.h): its output
  // goes to the process's render.log, an exception fails the cases it was to render (exit 2 for
  // InputError, 1 otherwise, its message in the report), and a crash or a hang past timeoutS
  // fails them too, not the run. Required.
  RenderStudy render;
};

// True when every case passes. Throws InputError (naming the suite or a study) for a bad
// suite, before anything renders. Forks a process launcher as it starts (ProcessPool): call it
// before starting threads whose state the render function needs.
bool runValidate(const ValidateOptions& options);

}  // namespace mvw::validate
