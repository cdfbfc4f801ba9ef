#pragma once
#include <CLI/App.hpp>

namespace mvw::app {

// `mvw pacs echo|find|get|store SERVER ...`: a PACS over DICOMweb or DIMSE (issue 37).
void addPacsCommand(CLI::App& app);

}  // namespace mvw::app
