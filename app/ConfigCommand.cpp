#include "ConfigCommand.h"

#include <iostream>

#include <CLI/CLI.hpp>

#include "mvw/config/ConfigReference.h"

namespace mvw::app {

void addConfigCommand(CLI::App& app) {
  CLI::App* config = app.add_subcommand("config", "About study configs (JSON)");
  config->require_subcommand(1);
  CLI::App* reference = config->add_subcommand(
      "reference",
      "Print the study config reference (every key: type, values, default, description) as "
      "Markdown, as docs/config-reference.md has it");
  reference->callback([] { std::cout << config::studyConfigReference() << std::flush; });
}

}  // namespace mvw::app
