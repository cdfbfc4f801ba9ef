#include "ValidateCommand.h"

#include "CliChecks.h"
#include "CommandBody.h"
#include "HeadlessGl.h"

#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "mvw/core/ExitCode.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/process/ProcessPool.h"
#include "mvw/validate/Validator.h"

namespace mvw::app {

namespace {

struct ValidateCli {
  validate::ValidateOptions options;
  std::string gl;  // --gl for every render (empty: MVW_GL, else auto)
};

}  // namespace

void addValidateCommand(CLI::App& app, const pacs::Options& pacs) {
  auto o = std::make_shared<ValidateCli>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Render a validation suite headless, compare with reference images, write an HTML report");
  cmd->add_option("suite", o->options.suite, "Suite file (.json)")->required();
  cmd->add_option("-o,--output", o->options.outDir,
                  "Report folder (index.html, report.json, cases/)")
      ->required();
  cmd->add_flag("--update", o->options.update,
                "Rewrite the reference images with the new renders (review them!)");
  cmd->add_option("-j,--jobs", o->options.jobs,
                  "Render processes at once (each study's cases are shared among at most N)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--timeout", o->options.timeoutS,
                  "Seconds one render process (its share of a study's cases) may take")
      ->check(positive());
  addGlOption(*cmd, o->gl);
  setCommandBody(*cmd, [o, &pacs] {
    // A backend the user named must exist here (exit 2 now, not one failure per case). The
    // probe context is made in a child process: the renders are forked from this one, which
    // makes no GL context (a driver's threads and state do not survive a fork).
    if (!o->gl.empty() || output::resolveGl("").request != render::GlRequest::Auto) {
      const int status = process::runInChild([gl = o->gl] { output::makeHeadlessContext(gl); });
      if (status != 0) return status;  // the child said why on stderr
    }
    o->options.gl = o->gl;
    o->options.pacs = pacs;
    // A failing case is neither bad input nor an internal fault, and the report said why: exit
    // 1 without a message.
    return validate::runValidate(o->options) ? kExitSuccess : kExitFailure;
  });
}

}  // namespace mvw::app
