#pragma once
// `mvw batch report`: every study's result in OUT merged into OUT/summary.csv (one row per study
// of the manifest: id, status done | failed | not run, time, exit code, message, the first ROI's
// statistics), OUT/stats.csv (every ROI of every stats study) and OUT/index.html (a thumbnail per
// rendered view, the statistics, each failure with its message).
#include <filesystem>
#include <string>
#include <vector>

namespace mvw::validate {

// What `mvw batch run` leaves in OUT/batch.json: the manifest and its ids, in order.
void writeBatchIndex(const std::filesystem::path& out, const std::filesystem::path& manifest,
                     const std::vector<std::string>& ids);

struct BatchReportCounts {
  int done = 0, failed = 0, notRun = 0;
};

// Throws InputError naming OUT when it holds no batch.json (no `mvw batch run` wrote there).
BatchReportCounts writeBatchReport(const std::filesystem::path& out);

}  // namespace mvw::validate
