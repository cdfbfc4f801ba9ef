#pragma once
// `mvw batch report`: every study's result in OUT merged into OUT/summary.csv (one row per study
// of the manifest: id, status done | failed | not run, time, exit code, message, the first ROI's
// statistics and the names of all its ROIs), OUT/stats.csv (every ROI of every stats study) and
// OUT/index.html: the counts, the failures grouped by message, a histogram of the studies'
// durations, then the studies (a thumbnail per rendered view, an orbit by its first frame and a
// link to the rest, the statistics, each failure with its message). A cohort too large for one
// page (over 500 studies or 2 MB) gets its studies on pages OUT/pages/NNNN.html, which the index
// lists, so no HTML file grows with the cohort and a thumbnail loads only on its study's page.
// The CSV files are written as the studies are read, never held whole.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace mvw::batch {

// What `mvw batch run` leaves in OUT/batch.json: the manifest and its ids, in order.
void writeBatchIndex(const std::filesystem::path& out, const std::filesystem::path& manifest,
                     const std::vector<std::string>& ids);

struct BatchReportCounts {
  int done = 0, failed = 0, notRun = 0;
};

// The report's files as text, from OUT's batch.json and each study's done.json or failed.json
// (and its render.json, stats.json): nothing is written. `pages` (name relative to OUT, text) is
// empty when the studies fit index.html. Throws InputError naming OUT when it holds no
// batch.json (no `mvw batch run` wrote there).
struct BatchReportFiles {
  BatchReportCounts counts;
  std::string summaryCsv, statsCsv, indexHtml;
  std::vector<std::pair<std::string, std::string>> pages;
};
struct BatchReportPaging {
  int studies = 500;              // at most this many studies on a page
  std::size_t bytes = 2'000'000;  // a page is closed once it holds this much HTML
};
BatchReportFiles buildBatchReport(const std::filesystem::path& out,
                                  const BatchReportPaging& paging = {});

// The same files written, each atomically: the CSVs streamed as the studies are read, each page
// when it is full, index.html last; pages of an earlier, larger report are removed.
BatchReportCounts writeBatchReport(const std::filesystem::path& out,
                                   const BatchReportPaging& paging = {});

}  // namespace mvw::batch
