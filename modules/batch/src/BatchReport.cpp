#include "mvw/batch/BatchReport.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

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

const char* kStatColumns[] = {"voxels", "volume_ml",          "max", "mean", "sd",
                              "peak",   "metabolic_volume_ml"};

}  // namespace

void writeBatchIndex(const fs::path& out, const fs::path& manifest,
                     const std::vector<std::string>& ids) {
  nlohmann::json j;
  j["manifest"] = fs::absolute(manifest).lexically_normal().string();
  j["ids"] = ids;
  io::writeTextAtomically(out / "batch.json", j.dump(1) + "\n");
}

BatchReportFiles buildBatchReport(const fs::path& out) {
  const nlohmann::json index = detail::readJsonOrNull(out / "batch.json");
  if (!index.is_object() || !index.contains("ids") || !index["ids"].is_array())
    throw InputError(out, "holds no batch.json: it is not the output folder of `mvw batch run`");
  BatchReportCounts counts;
  std::ostringstream summary, stats, body, failures;
  summary << "id,status,task,seconds,exit_code,message,roi,unit";
  for (const char* c : kStatColumns) summary << "," << c;
  summary << "\n";
  stats << "id,roi,label,unit";
  for (const char* c : kStatColumns) stats << "," << c;
  stats << "\n";
  for (const auto& idJson : index["ids"]) {
    const std::string id = idJson.get<std::string>();
    const fs::path dir = out / id;
    nlohmann::json done = detail::readJsonOrNull(dir / "done.json");
    const nlohmann::json failed = detail::readJsonOrNull(dir / "failed.json");
    std::string status = "not run", task, message, seconds, exitCode;
    if (done.is_object()) {
      status = "done";
      ++counts.done;
    } else if (failed.is_object()) {
      status = "failed";
      ++counts.failed;
      message = failed.value("message", "");
      exitCode = std::to_string(failed.value("exit_code", -1));
    } else {
      ++counts.notRun;
    }
    const nlohmann::json& marker = done.is_object() ? done : failed;
    if (marker.is_object()) {
      task = marker.value("task", "");
      seconds = num(marker.value("seconds", nlohmann::json()));
    }
    summary << csv(id) << "," << status << "," << task << "," << seconds << "," << exitCode << ","
            << csv(message);
    // A stats study: its ROIs; the first in summary.csv, all in stats.csv.
    nlohmann::json rois =
        status == "done" && task == "stats" ? detail::readJsonOrNull(dir / "stats.json") : nullptr;
    if (rois.is_object()) rois = nlohmann::json::array({rois});
    if (rois.is_array() && !rois.empty()) {
      const auto& first = rois[0];
      summary << "," << csv(first.value("roi", "")) << "," << csv(first.value("unit", ""));
      for (const char* c : kStatColumns) summary << "," << num(first.value(c, nlohmann::json()));
      for (const auto& r : rois) {
        stats << csv(id) << "," << csv(r.value("roi", "")) << ","
              << (r.contains("label") ? num(r["label"]) : "") << "," << csv(r.value("unit", ""));
        for (const char* c : kStatColumns) stats << "," << num(r.value(c, nlohmann::json()));
        stats << "\n";
      }
    } else {
      summary << ",,";
      for (std::size_t i = 0; i < std::size(kStatColumns); ++i) summary << ",";
    }
    summary << "\n";

    body << "<section id=\"" << html(id) << "\" class=\""
         << (status == "done"     ? "done"
             : status == "failed" ? "failed"
                                  : "notrun")
         << "\"><h2>" << html(id) << " <small>" << status << (task.empty() ? "" : " · " + task)
         << (seconds.empty() ? "" : " · " + oneDecimal(marker["seconds"]) + " s")
         << "</small></h2>\n";
    if (status == "failed") {
      // The log is linked only where it is: a study stopped before its command ran may have
      // none (a run of an older mvw).
      body << "<p class=\"message\">exit " << exitCode << ": " << html(message);
      if (fs::is_regular_file(dir / "log.txt"))
        body << " (<a href=\"" << html(id) << "/log.txt\">log</a>)";
      body << "</p>\n";
      failures << "<li><a href=\"#" << html(id) << "\">" << html(id) << "</a>: exit " << exitCode
               << ": " << html(message) << "</li>\n";
    }
    if (status == "done" && done.contains("outputs")) {
      // The views in the study config's order (render.json lists them so), then any other image
      // (the registration's QA picture) by name.
      std::vector<std::string> images;
      const nlohmann::json render = detail::readJsonOrNull(dir / "render.json");
      if (render.is_object() && render.contains("views") && render["views"].is_array())
        for (const auto& v : render["views"])
          if (v.is_object() && v.contains("file") && v["file"].is_string() &&
              done["outputs"].contains(v["file"].get<std::string>()))
            images.push_back(v["file"]);
      for (const auto& [file, sum] : done["outputs"].items())
        if (fs::path(file).extension() == ".png" &&
            std::find(images.begin(), images.end(), file) == images.end())
          images.push_back(file);
      for (const std::string& file : images) {
        body << "<figure><a href=\"" << html(id + "/" + file) << "\"><img loading=\"lazy\" src=\""
             << html(id + "/" + file) << "\"></a><figcaption>"
             << html(fs::path(file).stem().string()) << "</figcaption></figure>\n";
      }
    }
    if (rois.is_array() && !rois.empty()) {
      body << "<table><tr><th>ROI</th><th>unit</th>";
      for (const char* c : kStatColumns) body << "<th>" << c << "</th>";
      body << "</tr>\n";
      for (const auto& r : rois) {
        body << "<tr><td>" << html(r.value("roi", "")) << "</td><td>" << html(r.value("unit", ""))
             << "</td>";
        for (const char* c : kStatColumns)
          body << "<td>" << num(r.value(c, nlohmann::json())) << "</td>";
        body << "</tr>\n";
      }
      body << "</table>\n";
    }
    body << "</section>\n";
  }
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>mvw batch: " << counts.done
    << " done, " << counts.failed << " failed, " << counts.notRun << " not run</title>\n<style>\n"
    << "body{font-family:sans-serif;background:#111;color:#ddd;margin:1em}"
    << "a{color:#8cf}h2{margin:.2em 0}small{color:#999;font-weight:normal}"
    << "section{border-top:1px solid #333;padding:.5em 0}section.failed h2{color:#f77}"
    << "section.notrun h2{color:#fc6}.message{color:#f99;font-family:monospace}"
    << "figure{display:inline-block;margin:.3em;text-align:center}figure "
       "img{width:160px;height:160px;"
    << "object-fit:contain;background:#000}figcaption{font-size:.8em;color:#aaa}"
    << "table{border-collapse:collapse;font-size:.85em}td,th{border:1px solid #333;padding:.2em "
       ".5em;"
    << "text-align:right}td:first-child{text-align:left}\n</style></head><body>\n"
    << "<h1>mvw batch: " << counts.done << " done, " << counts.failed << " failed, "
    << counts.notRun << " not run</h1>\n<p>Manifest: " << html(index.value("manifest", ""))
    << " · <a href=\"summary.csv\">summary.csv</a> · "
    << "<a href=\"stats.csv\">stats.csv</a></p>\n";
  if (counts.failed) h << "<h2>Failures</h2><ul>\n" << failures.str() << "</ul>\n";
  h << body.str() << "</body></html>\n";
  return {counts, summary.str(), stats.str(), h.str()};
}

BatchReportCounts writeBatchReport(const fs::path& out) {
  const BatchReportFiles files = buildBatchReport(out);
  io::writeTextAtomically(out / "summary.csv", files.summaryCsv);
  io::writeTextAtomically(out / "stats.csv", files.statsCsv);
  io::writeTextAtomically(out / "index.html", files.indexHtml);
  return files.counts;
}

}  // namespace mvw::batch
