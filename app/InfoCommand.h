#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw info PATH...`: what each volume or DICOM series at PATH is, where it lies, in what unit.
void addInfoCommand(CLI::App& app);

}  // namespace mvw::app
