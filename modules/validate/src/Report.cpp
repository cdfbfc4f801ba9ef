#include "mvw/validate/Report.h"

#include <sstream>

#include "EmbeddedResources.h"
#include "Format.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::validate {

namespace fs = std::filesystem;
using detail::fmt;
using nlohmann::json;

namespace {

std::string html(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

json numberOrInf(double v) { return std::isfinite(v) ? json(v) : json("inf"); }

const char* verdict(const CaseResult& r) {
  return r.updated ? "updated" : r.pass ? "pass" : "FAIL";
}

}  // namespace

std::string caseLine(const CaseSpec& c, const CaseResult& r) {
  std::string s = (r.updated ? "UPDATED " : r.pass ? "PASS    " : "FAIL    ") + c.name;
  if (r.metrics)
    s += "  max " + fmt(r.metrics->maxDelta, 0) + " (" + fmt(100 * r.metrics->overFraction, 3) +
         "% > " + fmt(c.tolerance.maxDelta, 0) + ")  mean " + fmt(r.metrics->meanDelta, 3) +
         "  PSNR " + fmt(r.metrics->psnr, 2) + " dB  SSIM " + fmt(r.metrics->ssim, 4);
  for (const auto& ch : r.checks) s += std::string("  check ") + (ch.pass ? "ok" : "FAILED");
  if (!r.comparison.empty()) s += "  [" + r.comparison + "]";
  if (r.renderMs > 0) s += "  (render " + fmt(r.renderMs, 0) + " ms)";
  if (!r.updateNote.empty()) s += "\n          " + r.updateNote;
  for (const auto& p : r.problems) s += "\n          " + p;
  return s;
}

namespace {

json reportJson(const Suite& suite, const std::vector<CaseResult>& results, const json& environment,
                bool updated) {
  int passed = 0;
  for (const auto& r : results) passed += r.pass ? 1 : 0;
  json rj;
  rj["suite"] = fs::absolute(suite.file).string();
  rj["name"] = suite.name;
  rj["environment"] = environment;
  rj["passed"] = passed;
  rj["failed"] = static_cast<int>(results.size()) - passed;
  rj["updated"] = updated;
  rj["cases"] = json::array();
  for (std::size_t ci = 0; ci < suite.cases.size(); ++ci) {
    const CaseSpec& c = suite.cases[ci];
    const CaseResult& r = results[ci];
    json cj;
    cj["name"] = c.name;
    cj["study"] = c.study.string();
    cj["view"] = c.viewLabel;
    cj["pass"] = r.pass;
    cj["updated"] = r.updated;
    cj["render_ms"] = r.renderMs;
    cj["problems"] = r.problems;
    if (!r.comparison.empty()) cj["comparison"] = r.comparison;
    if (!r.updateNote.empty()) cj["update"] = r.updateNote;
    if (c.reference) cj["reference"] = c.reference->string();
    cj["tolerance"] = {{"max_delta", c.tolerance.maxDelta},
                       {"max_delta_fraction", c.tolerance.maxDeltaFraction},
                       {"mean_delta", c.tolerance.meanDelta},
                       {"psnr", c.tolerance.psnr},
                       {"ssim", c.tolerance.ssim}};
    if (r.metrics)
      cj["metrics"] = {{"max_delta", r.metrics->maxDelta},
                       {"fraction_over_max_delta", r.metrics->overFraction},
                       {"mean_delta", r.metrics->meanDelta},
                       {"psnr_db", numberOrInf(r.metrics->psnr)},
                       {"ssim", r.metrics->ssim}};
    cj["checks"] = json::array();
    for (std::size_t k = 0; k < r.checks.size(); ++k) {
      const CheckResult& ch = r.checks[k];
      cj["checks"].push_back({{"type", c.checks[k].type},
                              {"pass", ch.pass},
                              {"message", ch.message},
                              {"psnr_db", numberOrInf(ch.psnr)},
                              {"worst", ch.worst},
                              {"pixels", ch.pixels}});
    }
    rj["cases"].push_back(cj);
  }
  return rj;
}

void summaryTable(std::ostream& h, const Suite& suite, const std::vector<CaseResult>& results) {
  h << "<table><tr><th>case</th><th>result</th><th>max delta</th><th>% over</th>"
       "<th>mean delta</th><th>PSNR dB</th><th>SSIM</th><th>checks</th></tr>\n";
  for (std::size_t ci = 0; ci < suite.cases.size(); ++ci) {
    const CaseSpec& c = suite.cases[ci];
    const CaseResult& r = results[ci];
    h << "<tr><td><a href=\"#" << html(c.name) << "\">" << html(c.name) << "</a></td><td class=\""
      << (r.pass ? "pass" : "fail") << "\">" << verdict(r) << "</td>";
    if (r.metrics)
      h << "<td>" << fmt(r.metrics->maxDelta, 0) << "</td><td>"
        << fmt(100 * r.metrics->overFraction, 3) << "</td><td>" << fmt(r.metrics->meanDelta, 3)
        << "</td><td>" << fmt(r.metrics->psnr, 2) << "</td><td>" << fmt(r.metrics->ssim, 4)
        << "</td>";
    else
      h << "<td colspan=\"5\">-</td>";
    int okChecks = 0;
    for (const auto& ch : r.checks) okChecks += ch.pass ? 1 : 0;
    h << "<td>" << okChecks << "/" << c.checks.size() << "</td></tr>\n";
  }
  h << "</table>\n";
}

void metricsTable(std::ostream& h, const Metrics& m, const Tolerance& t) {
  h << "<table><tr><th>metric</th><th>value</th><th>tolerance</th></tr>"
    << "<tr><td>max per-pixel delta</td><td>" << fmt(m.maxDelta, 0) << "</td><td>"
    << fmt(t.maxDelta, 0) << " on at most " << fmt(100 * t.maxDeltaFraction, 3)
    << "% of pixels</td></tr>"
    << "<tr><td>pixels over " << fmt(t.maxDelta, 0) << "</td><td>" << fmt(100 * m.overFraction, 3)
    << "%</td><td>&le; " << fmt(100 * t.maxDeltaFraction, 3) << "%</td></tr>"
    << "<tr><td>mean delta</td><td>" << fmt(m.meanDelta, 3) << "</td><td>&le; "
    << fmt(t.meanDelta, 3) << "</td></tr>"
    << "<tr><td>PSNR</td><td>" << fmt(m.psnr, 2) << " dB</td><td>&ge; " << fmt(t.psnr, 2)
    << " dB</td></tr>"
    << "<tr><td>SSIM</td><td>" << fmt(m.ssim, 4) << "</td><td>&ge; " << fmt(t.ssim, 4)
    << "</td></tr></table>\n";
}

void figure(std::ostream& h, const std::string& src, const std::string& caption) {
  h << "<figure><img src=\"" << html(src) << "\"><figcaption>" << caption
    << "</figcaption></figure>";
}

void caseSection(std::ostream& h, const CaseSpec& c, const CaseResult& r) {
  const std::string dir = "cases/" + c.name + "/";
  h << "<div class=\"case\" id=\"" << html(c.name) << "\"><h3>" << html(c.name) << " <span class=\""
    << (r.pass ? "pass" : "fail") << "\">" << verdict(r) << "</span></h3>\n";
  h << "<p>study " << html(c.study.string()) << ", view " << html(c.viewLabel);
  if (c.reference) h << ", reference " << html(c.reference->string());
  if (!r.comparison.empty()) h << ", compared " << html(r.comparison);
  if (r.renderMs > 0) h << " (render " << fmt(r.renderMs, 0) << " ms)";
  h << "</p>\n";
  if (!r.updateNote.empty()) h << "<p>" << html(r.updateNote) << "</p>\n";
  for (const auto& p : r.problems) h << "<p class=\"fail\">" << html(p) << "</p>\n";
  if (c.reference) {
    if (r.hasReference) figure(h, dir + "reference.png", "reference");
    if (r.hasRender) figure(h, dir + "render.png", "new render");
    if (r.hasDiff) figure(h, dir + "diff.png", "|delta| x 8");
    h << "\n";
    if (r.metrics) metricsTable(h, *r.metrics, c.tolerance);
  }
  for (std::size_t k = 0; k < r.checks.size(); ++k) {
    const CheckResult& ch = r.checks[k];
    const std::string tag = dir + "check" + std::to_string(k + 1) + "-";
    h << "<p>check " << k + 1 << " (" << html(c.checks[k].type) << "): <span class=\""
      << (ch.pass ? "pass" : "fail") << "\">" << (ch.pass ? "pass" : "FAIL") << "</span> "
      << html(ch.message) << "</p>\n";
    if (ch.pixels > 0) {
      figure(h, tag + "expected.png", "maximum projection (computed)");
      figure(h, tag + "render.png", "MIP render");
      figure(h, tag + "diff.png", "|delta| x 8");
      h << "\n";
    }
  }
  h << "</div>\n";
}

void replaceAll(std::string& text, const std::string& what, const std::string& with) {
  for (std::size_t at = text.find(what); at != std::string::npos;
       at = text.find(what, at + with.size()))
    text.replace(at, what.size(), with);
}

}  // namespace

std::string reportHtml(const Suite& suite, const std::vector<CaseResult>& results,
                       const json& environment, bool updated) {
  int passed = 0;
  for (const auto& r : results) passed += r.pass ? 1 : 0;
  const bool failed = passed != static_cast<int>(results.size());
  std::ostringstream h;
  h << "<h1>mvw validate: "
    << html(suite.name.empty() ? suite.file.filename().string() : suite.name) << "</h1>\n";
  h << "<p class=\"" << (failed ? "fail" : "pass") << "\">" << passed << " of " << results.size()
    << " cases pass" << (updated ? " (references updated)" : "") << "</p>\n";
  h << "<h2>Environment</h2><table>";
  h << "<tr><th>suite</th><td>" << html(fs::absolute(suite.file).string()) << "</td></tr>";
  for (const char* key :
       {"mvw_version", "gl_backend", "gl_renderer", "gl_version", "host", "date_utc", "jobs"}) {
    const json v = environment.contains(key) ? environment.at(key) : json();
    h << "<tr><th>" << key << "</th><td>" << html(v.is_string() ? v.get<std::string>() : v.dump())
      << "</td></tr>";
  }
  h << "</table>\n<h2>Cases</h2>\n";
  summaryTable(h, suite, results);
  for (std::size_t ci = 0; ci < suite.cases.size(); ++ci)
    caseSection(h, suite.cases[ci], results[ci]);
  std::string page(detail::embeddedResources().at("report.html"));
  replaceAll(page, "@TITLE@", html(suite.name));
  replaceAll(page, "@BODY@", h.str());
  return page;
}

void writeReport(const Suite& suite, const std::vector<CaseResult>& results,
                 const json& environment, bool updated, const fs::path& reportDir) {
  io::writeTextAtomically(reportDir / "report.json",
                          reportJson(suite, results, environment, updated).dump(2) + "\n");
  io::writeTextAtomically(reportDir / "index.html",
                          reportHtml(suite, results, environment, updated));
}

}  // namespace mvw::validate
