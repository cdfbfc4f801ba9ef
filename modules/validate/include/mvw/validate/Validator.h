#pragma once
// `mvw validate`: every case of a suite rendered headless through `mvw render` (child
// processes, N at a time; the renders of one study are dealt to at most N of them), compared
// with its reference under the case's tolerances, its analytic checks run, and the report
// written. See app/ValidateCommand.h for the format.
#include <filesystem>
#include <string>

namespace mvw::validate {

struct ValidateOptions {
  std::filesystem::path suite;
  std::filesystem::path outDir;
  bool update = false;  // rewrite the references with the new renders
  int jobs = 1;
  double timeoutS = 600.0;  // per `mvw render` process
  std::string gl;  // `--gl` passed to every render (empty: none, so MVW_GL or auto decides)
  std::filesystem::path executable;  // the `mvw` binary that renders (default: this process's)
};

// True when every case passes. Throws InputError (naming the suite or a study) for a bad
// suite, before anything renders.
bool runValidate(const ValidateOptions& options);

}  // namespace mvw::validate
