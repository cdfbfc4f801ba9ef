#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw render STUDY.json -o DIR`: headless renders of the views the config lists, one PNG
// per view plus render.json (parameters, GL renderer, time per frame, image checksum), by
// output::renderStudy.
void addRenderCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
