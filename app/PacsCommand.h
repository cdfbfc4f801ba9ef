#pragma once
#include <string>

#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw pacs echo|find|get|store SERVER ...`: a PACS over DICOMweb or DIMSE (issue 37).
void addPacsCommand(CLI::App& app);

// --calling-aet and --insecure: the connection options of `mvw pacs` that `--store SERVER` on
// render, register and stats shares (their time-outs are the global --connect-timeout and
// --read-timeout; credentials come from the environment, as for `mvw pacs`).
void addServerOptions(CLI::App& cmd, pacs::Options& options);

// "stored 3 instances, 1.2 MB in 0.05 s (24.0 MB/s)": what `mvw pacs get|store` prints.
std::string transferSummary(const char* verb, const pacs::Transfer& t);

}  // namespace mvw::app
