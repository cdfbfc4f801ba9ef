#pragma once
// `mvw batch report`: every study's result in OUT merged into OUT/summary.csv (one row per study
// of the manifest: id, status done | failed | not run, time, exit code, message, the first ROI's
// statistics), OUT/stats.csv (every ROI of every stats study) and OUT/index.html (a thumbnail per
// rendered view, the statistics, each failure with its message).
#include <filesystem>
#include <string>
#include <vector>

namespace mvw::batch {

// What `mvw batch run` leaves in OUT/batch.json: the manifest and its ids, in order.
void writeBatchIndex(const std::filesystem::path& out, const std::filesystem::path& manifest,
                     const std::vector<std::string>& ids);

struct BatchReportCounts {
  int done = 0, failed = 0, notRun = 0;
};

// The report's three files as text, from OUT's batch.json and each study's done.json or
// failed.json (and its render.json, stats.json): nothing is written. Throws InputError naming
// OUT when it holds no batch.json (no `mvw batch run` wrote there).
struct BatchReportFiles {
  BatchReportCounts counts;
  std::string summaryCsv, statsCsv, indexHtml;
};
BatchReportFiles buildBatchReport(const std::filesystem::path& out);

// buildBatchReport, then OUT/summary.csv, OUT/stats.csv and OUT/index.html written atomically.
BatchReportCounts writeBatchReport(const std::filesystem::path& out);

}  // namespace mvw::batch
