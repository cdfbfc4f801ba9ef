#pragma once
// The options that make render, register and stats write DICOM objects (--dicom, --seg) and
// send them to a PACS (--store SERVER), the checks of which options go together, and the store
// said on the command's output. The rest is output::checkDicomDestination and storeDicom.
#include <filesystem>
#include <iosfwd>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvw/output/DicomOutput.h"

namespace mvw::app {

using DicomOutputOptions = output::DicomOutputOptions;

// --patient-id, --patient-name, --uid-root, --store SERVER (with `mvw pacs`'s --calling-aet and
// --insecure); with withFolder, --dicom and --force.
void addDicomOptions(CLI::App& cmd, DicomOutputOptions& o, bool withFolder);

// Before any work: the DICOM options (--store among them) go with a DICOM output (writing:
// --dicom or --seg), then output::checkDicomDestination. Throws CLI::ValidationError or
// InputError naming the folder or the server.
void checkDicomOutput(const DicomOutputOptions& o, bool writing,
                      const std::filesystem::path& outDir);

// With --store: output::storeDicom with the time-outs of `timeouts` (the command line's
// --connect-timeout and --read-timeout, those the study's PACS series are read with), and one
// line said on `out`.
void storeDicom(const DicomOutputOptions& o, const pacs::Options& timeouts,
                const std::vector<std::filesystem::path>& files, const std::filesystem::path& where,
                std::ostream& out);

}  // namespace mvw::app
