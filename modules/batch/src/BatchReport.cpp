#include "mvw/batch/BatchReport.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "JsonFile.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s)
    out += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return out + "\"";
}

std::string html(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string num(const nlohmann::json& v) {
  if (!v.is_number()) return "";
  return shortNumber(v.get<double>());
}

std::string oneDecimal(const nlohmann::json& v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v.is_number() ? v.get<double>() : 0.0);
  return buf;
}

// summary.csv and stats.csv carry them all; a study's HTML table the last two only where a ROI
// has them (a PET's metabolic mean and TLG).
const char* kStatColumns[] = {
    "voxels",         "volume_ml", "max", "mean", "sd", "peak", "metabolic_volume_ml",
    "metabolic_mean", "tlg"};
constexpr std::size_t kAlwaysShown = 7;

// The duration histogram's bins: upper bounds in seconds, and their labels.
const double kBinEnds[] = {1, 2, 5, 10, 30, 60, 120, 300, 600, 1800, 3600, 1e300};
const char* const kBinLabels[] = {"&lt; 1 s", "1-2 s",     "2-5 s",     "5-10 s",
                                  "10-30 s",  "30-60 s",   "1-2 min",   "2-5 min",
                                  "5-10 min", "10-30 min", "30-60 min", "&ge; 1 h"};
constexpr std::size_t kBins = std::size(kBinEnds);

// The failures shown by message on the first page, and the studies named in each.
constexpr std::size_t kFailureGroupsShown = 100;
constexpr std::size_t kIdsPerGroupShown = 20;

const char* const kStyle =
    "body{font-family:sans-serif;background:#111;color:#ddd;margin:1em}"
    "a{color:#8cf}h2{margin:.2em 0}small{color:#999;font-weight:normal}"
    "section{border-top:1px solid #333;padding:.5em 0}section.failed h2{color:#f77}"
    "section.notrun h2{color:#fc6}.message{color:#f99;font-family:monospace}"
    "figure{display:inline-block;margin:.3em;text-align:center}figure "
    "img{width:160px;height:160px;"
    "object-fit:contain;background:#000}figcaption{font-size:.8em;color:#aaa}"
    "table{border-collapse:collapse;font-size:.85em}td,th{border:1px solid #333;padding:.2em "
    ".5em;"
    "text-align:right}td:first-child{text-align:left}"
    ".bar{background:#8cf;height:.8em}td.bar-cell{text-align:left;width:320px}\n";

std::string pageName(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "page-%04d.html", k);
  return buf;
}

std::string countsText(const BatchReportCounts& c) {
  return std::to_string(c.done) + " done, " + std::to_string(c.failed) + " failed, " +
         std::to_string(c.notRun) + " not run";
}

// One study, as the report reads it from its folder.
struct StudyResult {
  std::string id, status = "not run", task, message, seconds, exitCode;
  nlohmann::json marker, rois;
};

StudyResult readStudy(const fs::path& out, const std::string& id) {
  StudyResult r;
  r.id = id;
  const fs::path dir = out / id;
  nlohmann::json done = detail::readJsonOrNull(dir / "done.json");
  if (done.is_object()) {
    r.status = "done";
    r.marker = std::move(done);
  } else {
    nlohmann::json failed = detail::readJsonOrNull(dir / "failed.json");
    if (failed.is_object()) {
      r.status = "failed";
      r.message = failed.value("message", "");
      r.exitCode = std::to_string(failed.value("exit_code", -1));
      r.marker = std::move(failed);
    }
  }
  if (r.marker.is_object()) {
    r.task = r.marker.value("task", "");
    r.seconds = num(r.marker.value("seconds", nlohmann::json()));
  }
  // A stats study: its ROIs; the first in summary.csv, all in stats.csv.
  if (r.status == "done" && r.task == "stats") r.rois = detail::readJsonOrNull(dir / "stats.json");
  if (r.rois.is_object()) r.rois = nlohmann::json::array({r.rois});
  if (!r.rois.is_array()) r.rois = nlohmann::json::array();
  return r;
}

void summaryRow(std::ostream& summary, const StudyResult& r) {
  summary << csv(r.id) << "," << r.status << "," << r.task << "," << r.seconds << "," << r.exitCode
          << "," << csv(r.message);
  if (!r.rois.empty()) {
    const auto& first = r.rois[0];
    summary << "," << csv(first.value("roi", "")) << "," << csv(first.value("unit", ""));
    for (const char* c : kStatColumns) summary << "," << num(first.value(c, nlohmann::json()));
  } else {
    summary << ",,";
    for (std::size_t i = 0; i < std::size(kStatColumns); ++i) summary << ",";
  }
  // Every ROI by name (their statistics are stats.csv's rows).
  std::string names;
  for (const auto& roi : r.rois) names += (names.empty() ? "" : "; ") + roi.value("roi", "");
  summary << "," << (r.rois.empty() ? "" : std::to_string(r.rois.size())) << "," << csv(names)
          << "\n";
}

void statsRows(std::ostream& stats, const StudyResult& r) {
  for (const auto& roi : r.rois) {
    stats << csv(r.id) << "," << csv(roi.value("roi", "")) << ","
          << (roi.contains("label") ? num(roi["label"]) : "") << "," << csv(roi.value("unit", ""));
    for (const char* c : kStatColumns) stats << "," << num(roi.value(c, nlohmann::json()));
    stats << "\n";
  }
}

// The images of a done study: the views in the study config's order (render.json lists them
// so), each orbit by its first frame (the view's still) with a link to its frames and movie,
// then any other image (the registration's QA picture) by name.
void figures(std::ostream& body, const fs::path& dir, const StudyResult& r) {
  const nlohmann::json& outputs = r.marker["outputs"];
  std::vector<std::pair<std::string, std::string>> images;  // file, the orbit's links
  std::vector<std::string> orbitFrames;
  const nlohmann::json render = detail::readJsonOrNull(dir / "render.json");
  if (render.is_object() && render.contains("views") && render["views"].is_array())
    for (const auto& v : render["views"]) {
      if (!v.is_object()) continue;
      std::string orbit;
      if (v.contains("orbit") && v["orbit"].is_object()) {
        const nlohmann::json& o = v["orbit"];
        std::size_t frames = 0;
        if (o.contains("files") && o["files"].is_array())
          for (const auto& f : o["files"])
            if (f.is_string()) {
              orbitFrames.push_back(f);
              ++frames;
            }
        const std::string folder = o.value("folder", ""), movie = o.value("movie", "");
        if (!folder.empty())
          orbit += " · <a href=\"" + html(r.id + "/" + folder) +
                   "/\">orbit: " + countOf(frames, "frame") + "</a>";
        if (!movie.empty()) orbit += " · <a href=\"" + html(r.id + "/" + movie) + "\">movie</a>";
      }
      if (v.contains("file") && v["file"].is_string() &&
          outputs.contains(v["file"].get<std::string>()))
        images.emplace_back(v["file"], orbit);
    }
  const auto listed = [&](const std::string& file) {
    return std::find(orbitFrames.begin(), orbitFrames.end(), file) != orbitFrames.end() ||
           std::find_if(images.begin(), images.end(),
                        [&](const auto& i) { return i.first == file; }) != images.end();
  };
  for (const auto& [file, sum] : outputs.items())
    if (fs::path(file).extension() == ".png" && !listed(file)) images.emplace_back(file, "");
  for (const auto& [file, orbit] : images)
    body << "<figure><a href=\"" << html(r.id + "/" + file) << "\"><img loading=\"lazy\" src=\""
         << html(r.id + "/" + file) << "\"></a><figcaption>" << html(fs::path(file).stem().string())
         << orbit << "</figcaption></figure>\n";
}

std::string section(const fs::path& out, const StudyResult& r) {
  std::ostringstream body;
  body << "<section id=\"" << html(r.id) << "\" class=\""
       << (r.status == "done"     ? "done"
           : r.status == "failed" ? "failed"
                                  : "notrun")
       << "\"><h2>" << html(r.id) << " <small>" << r.status
       << (r.task.empty() ? "" : " · " + r.task)
       << (r.seconds.empty() ? "" : " · " + oneDecimal(r.marker["seconds"]) + " s")
       << "</small></h2>\n";
  if (r.status == "failed") {
    // The log is linked only where it is: a study stopped before its command ran may have none
    // (a run of an older mvw).
    body << "<p class=\"message\">exit " << r.exitCode << ": " << html(r.message);
    if (fs::is_regular_file(out / r.id / "log.txt"))
      body << " (<a href=\"" << html(r.id) << "/log.txt\">log</a>)";
    body << "</p>\n";
  }
  if (r.status == "done" && r.marker.contains("outputs") && r.marker["outputs"].is_object())
    figures(body, out / r.id, r);
  if (!r.rois.empty()) {
    std::size_t shown = kAlwaysShown;
    for (const auto& roi : r.rois)
      for (std::size_t c = kAlwaysShown; c < std::size(kStatColumns); ++c)
        if (roi.contains(kStatColumns[c]) && roi[kStatColumns[c]].is_number())
          shown = std::size(kStatColumns);
    body << "<table><tr><th>ROI</th><th>unit</th>";
    for (std::size_t c = 0; c < shown; ++c) body << "<th>" << kStatColumns[c] << "</th>";
    body << "</tr>\n";
    for (const auto& roi : r.rois) {
      body << "<tr><td>" << html(roi.value("roi", "")) << "</td><td>" << html(roi.value("unit", ""))
           << "</td>";
      for (std::size_t c = 0; c < shown; ++c)
        body << "<td>" << num(roi.value(kStatColumns[c], nlohmann::json())) << "</td>";
      body << "</tr>\n";
    }
    body << "</table>\n";
  }
  body << "</section>\n";
  return body.str();
}

std::string pageHead(const std::string& title) {
  return "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + title +
         "</title>\n<style>\n" + kStyle + "</style></head><body>\n";
}

// Where the report's files go: the CSVs as streams, each page and the index whole.
struct Sinks {
  std::ostream& summary;
  std::ostream& stats;
  std::function<void(const std::string& name, const std::string& text)> file;
};

struct FailureGroup {
  std::string exitCode, message;
  int count = 0;
  std::vector<std::pair<std::string, int>> ids;  // the first few, with their page (0: index)
};

struct PageInfo {
  std::string first, last;
  BatchReportCounts counts;
};

BatchReportCounts report(const fs::path& out, const BatchReportPaging& paging, Sinks& sinks) {
  const nlohmann::json index = detail::readJsonOrNull(out / "batch.json");
  if (!index.is_object() || !index.contains("ids") || !index["ids"].is_array())
    throw InputError(out, "holds no batch.json: it is not the output folder of `mvw batch run`");
  sinks.summary << "id,status,task,seconds,exit_code,message,roi,unit";
  for (const char* c : kStatColumns) sinks.summary << "," << c;
  sinks.summary << ",rois,roi_names\n";
  sinks.stats << "id,roi,label,unit";
  for (const char* c : kStatColumns) sinks.stats << "," << c;
  sinks.stats << "\n";

  BatchReportCounts counts;
  std::vector<FailureGroup> groups;
  std::unordered_map<std::string, std::size_t> groupOf;
  std::array<int, kBins> histogram{};
  std::vector<PageInfo> pages;
  std::string body;  // the page being filled
  int onPage = 0;
  const std::string manifest = html(index.value("manifest", ""));

  // A full page is written with links to its neighbours; the last one only once it is known
  // that the studies do not fit the index.
  const auto writePage = [&](bool more) {
    const int k = static_cast<int>(pages.size());
    std::ostringstream h;
    const std::string range = html(pages.back().first) + " … " + html(pages.back().last);
    h << pageHead("mvw batch: page " + std::to_string(k) + ", " + range) << "<h1>mvw batch: page "
      << k << " <small>" << range << " · " << countsText(pages.back().counts)
      << "</small></h1>\n<p><a href=\"index.html\">index</a>";
    if (k > 1) h << " · <a href=\"" << pageName(k - 1) << "\">previous</a>";
    if (more) h << " · <a href=\"" << pageName(k + 1) << "\">next</a>";
    h << " · Manifest: " << manifest << "</p>\n" << body << "</body></html>\n";
    sinks.file(pageName(k), h.str());
    body.clear();
    onPage = 0;
  };

  for (const auto& idJson : index["ids"]) {
    const StudyResult r = readStudy(out, idJson.get<std::string>());
    if (r.status == "done")
      ++counts.done;
    else if (r.status == "failed")
      ++counts.failed;
    else
      ++counts.notRun;
    summaryRow(sinks.summary, r);
    statsRows(sinks.stats, r);
    if (r.marker.is_object() && r.marker.contains("seconds") && r.marker["seconds"].is_number()) {
      const double s = r.marker["seconds"].get<double>();
      std::size_t bin = 0;
      while (bin + 1 < kBins && s >= kBinEnds[bin]) ++bin;
      ++histogram[bin];
    }

    const std::string text = section(out, r);
    if (onPage > 0 && (onPage >= paging.studies || body.size() + text.size() > paging.bytes))
      writePage(true);
    if (onPage == 0) pages.push_back({r.id, r.id, {}});
    PageInfo& page = pages.back();
    page.last = r.id;
    (r.status == "done"     ? page.counts.done
     : r.status == "failed" ? page.counts.failed
                            : page.counts.notRun)++;
    body += text;
    ++onPage;

    if (r.status == "failed") {
      const std::string key = r.exitCode + "\n" + r.message;
      auto [it, fresh] = groupOf.emplace(key, groups.size());
      if (fresh) groups.push_back({r.exitCode, r.message, 0, {}});
      FailureGroup& g = groups[it->second];
      ++g.count;
      if (g.ids.size() < kIdsPerGroupShown)
        g.ids.emplace_back(r.id, static_cast<int>(pages.size()));
    }
  }
  const bool paged = pages.size() > 1;
  if (paged) writePage(false);

  std::ostringstream h;
  h << pageHead("mvw batch: " + countsText(counts)) << "<h1>mvw batch: " << countsText(counts)
    << "</h1>\n<p>Manifest: " << manifest << " · <a href=\"summary.csv\">summary.csv</a> · "
    << "<a href=\"stats.csv\">stats.csv</a></p>\n";
  if (counts.failed) {
    // By message, the most frequent first; a message met once reads as that study's failure.
    std::stable_sort(
        groups.begin(), groups.end(),
        [](const FailureGroup& a, const FailureGroup& b) { return a.count > b.count; });
    const auto link = [&](const std::pair<std::string, int>& id) {
      return "<a href=\"" + (paged ? pageName(id.second) : std::string()) + "#" + html(id.first) +
             "\">" + html(id.first) + "</a>";
    };
    h << "<h2>Failures</h2><ul>\n";
    for (std::size_t k = 0; k < groups.size() && k < kFailureGroupsShown; ++k) {
      const FailureGroup& g = groups[k];
      if (g.count == 1) {
        h << "<li>" << link(g.ids[0]) << ": exit " << g.exitCode << ": " << html(g.message)
          << "</li>\n";
        continue;
      }
      h << "<li>" << countOf(g.count, "study", "studies") << ": exit " << g.exitCode << ": "
        << html(g.message) << "<br>";
      for (std::size_t i = 0; i < g.ids.size(); ++i) h << (i ? ", " : "") << link(g.ids[i]);
      if (g.count > static_cast<int>(g.ids.size()))
        h << " and " << g.count - static_cast<int>(g.ids.size()) << " more (summary.csv)";
      h << "</li>\n";
    }
    if (groups.size() > kFailureGroupsShown)
      h << "<li>" << groups.size() - kFailureGroupsShown << " more messages (summary.csv)</li>\n";
    h << "</ul>\n";
  }
  const int most = *std::max_element(histogram.begin(), histogram.end());
  if (most > 0) {
    std::size_t from = 0, to = kBins;
    while (histogram[from] == 0) ++from;
    while (histogram[to - 1] == 0) --to;
    h << "<h2>Durations</h2><table>\n";
    for (std::size_t b = from; b < to; ++b)
      h << "<tr><td>" << kBinLabels[b] << "</td><td>" << histogram[b]
        << "</td><td class=\"bar-cell\"><div class=\"bar\" style=\"width:"
        << (300 * histogram[b] + most - 1) / most << "px\"></div></td></tr>\n";
    h << "</table>\n";
  }
  if (paged) {
    h << "<h2>Studies</h2><ul>\n";
    for (std::size_t k = 0; k < pages.size(); ++k)
      h << "<li><a href=\"" << pageName(static_cast<int>(k + 1)) << "\">" << html(pages[k].first)
        << " … " << html(pages[k].last) << "</a>: " << countsText(pages[k].counts) << "</li>\n";
    h << "</ul>\n";
  } else {
    h << body;
  }
  h << "</body></html>\n";
  sinks.file("index.html", h.str());
  return counts;
}

}  // namespace

void writeBatchIndex(const fs::path& out, const fs::path& manifest,
                     const std::vector<std::string>& ids) {
  nlohmann::json j;
  j["manifest"] = fs::absolute(manifest).lexically_normal().string();
  j["ids"] = ids;
  io::writeTextAtomically(out / "batch.json", j.dump(1) + "\n");
}

BatchReportFiles buildBatchReport(const fs::path& out, const BatchReportPaging& paging) {
  BatchReportFiles files;
  std::ostringstream summary, stats;
  Sinks sinks{summary, stats, [&](const std::string& name, const std::string& text) {
                if (name == "index.html")
                  files.indexHtml = text;
                else
                  files.pages.emplace_back(name, text);
              }};
  files.counts = report(out, paging, sinks);
  files.summaryCsv = summary.str();
  files.statsCsv = stats.str();
  return files;
}

BatchReportCounts writeBatchReport(const fs::path& out, const BatchReportPaging& paging) {
  BatchReportCounts counts;
  int pages = 0;
  // Both CSVs are streamed into their temporaries in one pass and renamed when it has ended.
  io::writeAtomically(out / "summary.csv", [&](const fs::path& summaryTmp) {
    io::writeAtomically(out / "stats.csv", [&](const fs::path& statsTmp) {
      std::ofstream summary(summaryTmp, std::ios::binary), stats(statsTmp, std::ios::binary);
      Sinks sinks{summary, stats, [&](const std::string& name, const std::string& text) {
                    if (name != "index.html") ++pages;
                    io::writeTextAtomically(out / name, text);
                  }};
      counts = report(out, paging, sinks);
      summary.close();
      stats.close();
      // As writeTextAtomically says it: a full disk may only show when the last buffer goes out.
      if (!summary || !stats)
        throw InputError(out / (summary ? "stats.csv" : "summary.csv"),
                         "cannot write (disk full or not writable?)");
    });
  });
  // An earlier report's pages beyond this one's (they are numbered without gaps).
  for (int k = pages + 1; fs::exists(out / pageName(k)); ++k) fs::remove(out / pageName(k));
  return counts;
}

}  // namespace mvw::batch
