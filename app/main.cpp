// mvw: multimodal volume workstation. One CLI, one subcommand per job.
// Exit codes: 0 success, 1 internal fault, 2 bad input (file, config or command line).
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "BenchCommand.h"
#include "ConvertCommand.h"
#include "GlyphMapCommand.h"
#include "InfoCommand.h"
#include "PhantomCommand.h"
#include "RegisterCommand.h"
#include "RenderCommand.h"
#include "StatsCommand.h"
#include "ValidateCommand.h"
#include "mvw/core/Error.h"
#include "mvw/core/Version.h"
#include "view/ViewCommand.h"

int main(int argc, char** argv) {
  CLI::App app{
      "mvw - multimodal volume workstation: anatomy + functional volumes, registered and rendered"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("mvw ") + mvw::kVersion);
  mvw::app::addInfoCommand(app);
  mvw::app::addConvertCommand(app);
  mvw::app::addRegisterCommand(app);
  mvw::app::addRenderCommand(app);
  mvw::app::addStatsCommand(app);
  mvw::app::addPhantomCommand(app);
  mvw::app::addGlyphMapCommand(app);
  mvw::app::addBenchCommand(app);
  mvw::app::addViewCommand(app);
  mvw::app::addValidateCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const mvw::InputError& e) {
    std::cerr << "mvw: error: " << e.what() << "\n";
    return 2;
  } catch (const mvw::Error& e) {
    std::cerr << "mvw: internal error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "mvw: internal error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mvw: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
