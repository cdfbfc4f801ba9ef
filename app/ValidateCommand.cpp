#include "ValidateCommand.h"

#include "CliChecks.h"
#include "HeadlessGl.h"

#include <cstdlib>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "mvw/validate/Validator.h"

namespace mvw::app {

void addValidateCommand(CLI::App& app) {
  auto o = std::make_shared<validate::ValidateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Render a validation suite headless, compare with reference images, write an HTML report");
  cmd->add_option("suite", o->suite, "Suite file (.json)")->required();
  cmd->add_option("-o,--output", o->outDir, "Report folder (index.html, report.json, cases/)")
      ->required();
  cmd->add_flag("--update", o->update,
                "Rewrite the reference images with the new renders (review them!)");
  cmd->add_option("-j,--jobs", o->jobs,
                  "Render processes at once (each study's cases are shared among at most N)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--timeout", o->timeoutS,
                  "Seconds one render process (its share of a study's cases) may take")
      ->check(positive());
  addGlOption(*cmd, o->gl);
  cmd->callback([o] {
    // A backend the user named must exist here (exit 2 now, not one failure per case). The
    // probe context is gone before the renders start.
    if (!o->gl.empty() || resolveGl("").request != render::GlRequest::Auto)
      makeHeadlessContext(o->gl);
    if (!validate::runValidate(*o)) {
      // A failing case is neither bad input nor an internal fault: exit 1 without a message.
      std::cout.flush();
      std::exit(1);
    }
  });
}

}  // namespace mvw::app
