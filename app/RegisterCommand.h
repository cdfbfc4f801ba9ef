#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw register --fixed ANATOMICAL --moving FUNCTIONAL -o DIR`: rigid mutual-information
// registration, the functional volume resampled onto the anatomical grid, and a report.
void addRegisterCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
