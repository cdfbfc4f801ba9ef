#pragma once
// What a validation run found, case by case, and the report it leaves: REPORT/report.json and
// REPORT/index.html (the HTML template is embedded from modules/validate/resources/).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvw/validate/ImageMetrics.h"
#include "mvw/validate/MipCheck.h"
#include "mvw/validate/Suite.h"

namespace mvw::validate {

struct CaseResult {
  bool pass = true;
  bool updated = false;
  std::vector<std::string> problems;
  std::optional<Metrics> metrics;
  std::vector<CheckResult> checks;
  double renderMs = 0;  // the case's views as `mvw render` timed them (render.json)
  bool hasRender = false, hasReference = false, hasDiff = false;
  // How the image was judged: "exact" (checksum and tolerances: the goldens' GL renderer),
  // "tolerance only" (another renderer, or no checksums), empty for check-only cases.
  std::string comparison;
  // --update: the old reference against the new render (PSNR, SSIM, mean/max abs delta),
  // "unchanged", or "new reference".
  std::string updateNote;
};

// One line per case for the terminal: PASS/FAIL/UPDATED, the metrics, the problems below.
std::string caseLine(const CaseSpec& spec, const CaseResult& result);

// environment: mvw_version, gl_backend, gl_renderer, gl_version, host, date_utc, jobs.
void writeReport(const Suite& suite, const std::vector<CaseResult>& results,
                 const nlohmann::json& environment, bool updated,
                 const std::filesystem::path& reportDir);

// The HTML report's text (for its unit test; writeReport writes it as index.html).
std::string reportHtml(const Suite& suite, const std::vector<CaseResult>& results,
                       const nlohmann::json& environment, bool updated);

}  // namespace mvw::validate
