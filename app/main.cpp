// mvw: multimodal volume workstation. One CLI, one subcommand per job.
// Exit codes (mvw/core/ExitCode.h): 0 success, 1 an internal fault or a failed comparison, 2 bad
// input (file, config or command line), 3 a server or the network failed (PACS, Slurm).
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>

#include <CLI/CLI.hpp>

#include "BatchCommand.h"
#include "BenchCommand.h"
#include "ConfigCommand.h"
#include "ConvertCommand.h"
#include "GlyphMapCommand.h"
#include "InfoCommand.h"
#include "PacsCommand.h"
#include "PhantomCommand.h"
#include "RegisterCommand.h"
#include "RenderCommand.h"
#include "StatsCommand.h"
#include "ValidateCommand.h"
#include "mvw/core/ExitCode.h"
#include "mvw/core/HugePages.h"
#include "mvw/core/Version.h"
#include "mvw/io/Interrupt.h"
#include "mvw/pacs/Pacs.h"
#include "view/ViewCommand.h"

int main(int argc, char** argv) {
  mvw::restartWithHugePages(argv, mvw::commandReadsVolumes(argv));
  // SIGINT and SIGTERM remove every staged output and exit 130 / 143 (io/Interrupt.h).
  mvw::io::installInterruptCleanup();
  CLI::App app{
      "mvw - multimodal volume workstation: anatomy + functional volumes, registered and rendered"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("mvw ") + mvw::kVersion);
  // Study configs naming PACS series: the verified cache and the time-outs, on every command
  // (fallthrough: given after the command's name too). Owned here and handed to each command
  // that reads a study, which passes them with its reads (study::localPath): nothing
  // process-wide configures a read that becomes a retrieve.
  mvw::pacs::Options pacsOptions;
  app.add_option("--cache", pacsOptions.cacheDir,
                 "the cache of PACS series (default $XDG_CACHE_HOME/mvw/dicom)");
  app.add_option("--connect-timeout", pacsOptions.connectTimeoutS,
                 "PACS: seconds to wait for the connection (default 10)")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--read-timeout", pacsOptions.readTimeoutS,
                 "PACS: seconds to wait for the next bytes of an answer (default 60)")
      ->check(CLI::Range(0.1, 86400.0));
  app.fallthrough();
  mvw::app::addInfoCommand(app, pacsOptions);
  mvw::app::addConvertCommand(app, pacsOptions);
  mvw::app::addRegisterCommand(app, pacsOptions);
  mvw::app::addRenderCommand(app, pacsOptions);
  mvw::app::addStatsCommand(app, pacsOptions);
  mvw::app::addPhantomCommand(app);
  mvw::app::addGlyphMapCommand(app);
  mvw::app::addBenchCommand(app, pacsOptions);
  mvw::app::addViewCommand(app, pacsOptions);
  mvw::app::addValidateCommand(app, pacsOptions);
  mvw::app::addConfigCommand(app);
  mvw::app::addBatchCommand(app, pacsOptions);
  mvw::app::addPacsCommand(app);
  // Every number option is finite: NaN passes any range check (comparisons with it are false)
  // and inf overflows what it scales.
  const CLI::Validator finite(
      [](std::string& text) {
        return std::isfinite(std::strtod(text.c_str(), nullptr))
                   ? std::string()
                   : "must be a finite number, not '" + text + "'";
      },
      "");
  std::function<void(CLI::App*)> requireFinite = [&](CLI::App* a) {
    for (CLI::Option* option : a->get_options())
      if (option->get_type_name().rfind("FLOAT", 0) == 0) option->check(finite);
    for (CLI::App* sub : a->get_subcommands({})) requireFinite(sub);
  };
  requireFinite(&app);
  // Everything but the command line itself ends through mvw::exitCodeOf, as mvw validate's
  // render processes do (mvw/core/ExitCode.h): one failure, one exit code, wherever it happens.
  return mvw::runReportingErrors(
      [&] {
        try {
          app.parse(argc, argv);  // runs the command
        } catch (const CLI::RuntimeError& e) {
          return e.get_exit_code();  // the command's own code (CommandBody.h), said already
        } catch (const CLI::ParseError& e) {
          if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
          // A command line mvw cannot use: one message in mvw's own form, exit 2.
          std::cerr << "mvw: error: " << e.what() << " (mvw COMMAND --help lists the options)\n";
          return mvw::kExitBadInput;
        }
        return mvw::kExitSuccess;
      },
      std::cerr);
}
