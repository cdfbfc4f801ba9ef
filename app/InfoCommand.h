#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw info PATH...`: what each volume or DICOM series at PATH is, where it lies, in what unit.
void addInfoCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
