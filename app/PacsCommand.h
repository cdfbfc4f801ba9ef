#pragma once
#include <string>

#include <CLI/App.hpp>

#include "mvw/pacs/MatchTable.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw pacs echo|find|get|store SERVER ...`: a PACS over DICOMweb or DIMSE (issue 37).
void addPacsCommand(CLI::App& app);

// --calling-aet and --insecure: the connection options of `mvw pacs` that `--store SERVER` on
// render, register and stats shares (their time-outs are the global --connect-timeout and
// --read-timeout; credentials come from the environment, as for `mvw pacs`).
void addServerOptions(CLI::App& cmd, pacs::Options& options);

// What `mvw pacs get|store` and --store print (DicomOutput.cpp).
using pacs::transferSummary;

}  // namespace mvw::app
