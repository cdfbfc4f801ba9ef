// The cohort's records and report (batch BatchRecord, BatchReport): done.json and failed.json as
// a run writes them, and summary.csv, stats.csv and index.html built from an output folder with
// a done render, a failed study, a study not run and a done stats study.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/batch/BatchRecord.h"
#include "mvw/batch/BatchReport.h"
#include "mvw/core/Error.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json readJson(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

BatchStudy studyOf(const std::string& id, const std::string& task) {
  BatchStudy s;
  s.id = id;
  s.study = "/cohort/" + id + ".json";
  s.task = task;
  s.line = id + ",/cohort/" + id + ".json," + task;
  return s;
}

const RecordContext kContext{"/cohort/cohort.csv", "0.9.1"};
const char* const kMessage = "mvw: error: /cohort/b.nii: is <bad> & \"odd\"";

// OUT with a: a done render (two views, render.json orders them), b: failed with exit 2, c: not
// run, d: a done stats study with two ROIs.
fs::path makeOutput() {
  const fs::path out = test::scratchDir() / "out";
  fs::create_directories(out);
  writeBatchIndex(out, "/cohort/cohort.csv", {"a", "b", "c", "d"});
  const BatchStudy a = studyOf("a", "render"), b = studyOf("b", "render"),
                   d = studyOf("d", "stats");
  fs::create_directories(out / "a");
  std::ofstream(out / "a" / "axial.png") << "png";
  std::ofstream(out / "a" / "coronal.png") << "png";
  std::ofstream(out / "a" / "render.json")
      << R"({"views": [{"file": "coronal.png"}, {"file": "axial.png"}]})";
  writeRecord(out / "a" / "done.json", doneRecord({&a, out / "a", {}, {"render"}}, kContext, 1.25));
  fs::create_directories(out / "b");
  writeRecord(out / "b" / "failed.json",
              failedRecord({&b, out / "b", {}, {"render"}}, kContext, 2, kMessage, 0.0));
  std::ofstream(out / "b" / "log.txt") << kMessage << "\n";
  fs::create_directories(out / "d");
  std::ofstream(out / "d" / "stats.json") << R"([
    {"roi": "whole", "unit": "SUV", "voxels": 100, "volume_ml": 1.5, "max": 3, "mean": 1.25,
     "sd": 0.5, "peak": 2.5, "metabolic_volume_ml": 0.75},
    {"roi": "hippo, left", "label": 37, "unit": "SUV", "voxels": 10, "volume_ml": 0.15,
     "max": 2, "mean": 1, "sd": 0.25, "peak": 1.5, "metabolic_volume_ml": 0.05}])";
  std::ofstream(out / "d" / "log.txt") << "working\n";
  writeRecord(out / "d" / "done.json", doneRecord({&d, out / "d", {}, {"stats"}}, kContext, 2.5));
  return out;
}

TEST(BatchRecord, FailedJsonHoldsTheStudyTheExitCodeAndTheMessage) {
  const fs::path dir = test::scratchDir();
  const BatchStudy b = studyOf("b", "register");
  const StudyRun run{&b, dir, {{"/cohort/b.json", "12ab"}}, {"register", "--fixed", "f.nii"}};
  writeRecord(dir / "failed.json", failedRecord(run, kContext, 3, "the PACS is down", 4.5));
  json j = readJson(dir / "failed.json");
  const std::string finished = j.at("finished_utc");
  EXPECT_TRUE(std::regex_match(finished, std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << finished;
  j.erase("finished_utc");
  EXPECT_EQ(j, json::parse(R"({"id": "b", "status": "failed", "task": "register", "seconds": 4.5,
    "command": ["register", "--fixed", "f.nii"], "manifest": "/cohort/cohort.csv",
    "manifest_line": "b,/cohort/b.json,register", "inputs": {"/cohort/b.json": "12ab"},
    "mvw_version": "0.9.1", "exit_code": 3, "message": "the PACS is down"})"));
  // Indented by 2, keys sorted, a final newline.
  std::ifstream in(dir / "failed.json");
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first, "{");
  EXPECT_EQ(second, "  \"command\": [");
}

TEST(BatchRecord, DoneJsonListsEveryOutputButTheLog) {
  const fs::path dir = test::scratchDir();
  fs::create_directories(dir / "dicom");
  std::ofstream(dir / "axial.png") << "png";
  std::ofstream(dir / "dicom" / "1.dcm") << "dcm";
  std::ofstream(dir / "log.txt") << "log";
  const BatchStudy a = studyOf("a", "render");
  const json j = doneRecord({&a, dir, {}, {"render"}}, kContext, 1.0);
  EXPECT_EQ(j.at("status"), "done");
  EXPECT_EQ(j.at("outputs"), (json{{"axial.png", process::fileSha256(dir / "axial.png")},
                                   {"dicom/1.dcm", process::fileSha256(dir / "dicom" / "1.dcm")}}));
  EXPECT_FALSE(j.contains("exit_code"));
}

TEST(BatchReport, CountsAndSummaryOfEveryStudy) {
  const fs::path out = makeOutput();
  EXPECT_EQ(readJson(out / "batch.json"),
            json::parse(R"({"manifest": "/cohort/cohort.csv", "ids": ["a", "b", "c", "d"]})"));
  const BatchReportFiles r = buildBatchReport(out);
  EXPECT_EQ(r.counts.done, 2);
  EXPECT_EQ(r.counts.failed, 1);
  EXPECT_EQ(r.counts.notRun, 1);
  EXPECT_EQ(r.summaryCsv,
            "id,status,task,seconds,exit_code,message,roi,unit,voxels,volume_ml,max,mean,sd,peak,"
            "metabolic_volume_ml\n"
            "a,done,render,1.25,,,,,,,,,,,\n"
            "b,failed,render,0,2,\"mvw: error: /cohort/b.nii: is <bad> & \"\"odd\"\"\",,,,,,,,,\n"
            "c,not run,,,,,,,,,,,,,\n"
            "d,done,stats,2.5,,,whole,SUV,100,1.5,3,1.25,0.5,2.5,0.75\n");
  EXPECT_EQ(r.statsCsv,
            "id,roi,label,unit,voxels,volume_ml,max,mean,sd,peak,metabolic_volume_ml\n"
            "d,whole,,SUV,100,1.5,3,1.25,0.5,2.5,0.75\n"
            "d,\"hippo, left\",37,SUV,10,0.15,2,1,0.25,1.5,0.05\n");
}

TEST(BatchReport, IndexHtmlListsFailuresViewsAndStatistics) {
  const fs::path out = makeOutput();
  const std::string html = buildBatchReport(out).indexHtml;
  const auto has = [&](const std::string& part) { return html.find(part) != std::string::npos; };
  EXPECT_TRUE(has("<title>mvw batch: 2 done, 1 failed, 1 not run</title>"));
  EXPECT_TRUE(
      has("<h1>mvw batch: 2 done, 1 failed, 1 not run</h1>\n<p>Manifest: "
          "/cohort/cohort.csv · <a href=\"summary.csv\">summary.csv</a>"));
  EXPECT_TRUE(
      has("<h2>Failures</h2><ul>\n<li><a href=\"#b\">b</a>: exit 2: mvw: error: "
          "/cohort/b.nii: is &lt;bad&gt; &amp; &quot;odd&quot;</li>\n</ul>\n"));
  EXPECT_TRUE(
      has("<section id=\"b\" class=\"failed\"><h2>b <small>failed · render · 0.0 "
          "s</small></h2>\n<p class=\"message\">exit 2: "));
  EXPECT_TRUE(has("(<a href=\"b/log.txt\">log</a>)</p>\n"));
  // A failed study without its log (an older mvw's, stopped before it ran): no link to nothing.
  fs::remove(out / "b" / "log.txt");
  const std::string noLog = buildBatchReport(out).indexHtml;
  EXPECT_EQ(noLog.find("b/log.txt"), std::string::npos);
  EXPECT_NE(noLog.find("&quot;odd&quot;</p>\n"), std::string::npos);
  EXPECT_TRUE(
      has("<section id=\"c\" class=\"notrun\"><h2>c <small>not run</small></h2>\n"
          "</section>\n"));
  // The views in render.json's order.
  const auto coronal = html.find("<img loading=\"lazy\" src=\"a/coronal.png\">");
  const auto axial = html.find("<img loading=\"lazy\" src=\"a/axial.png\">");
  ASSERT_NE(coronal, std::string::npos);
  ASSERT_NE(axial, std::string::npos);
  EXPECT_LT(coronal, axial);
  EXPECT_TRUE(
      has("<tr><td>hippo, left</td><td>SUV</td><td>10</td><td>0.15</td><td>2</td>"
          "<td>1</td><td>0.25</td><td>1.5</td><td>0.05</td></tr>\n"));
  EXPECT_TRUE(html.rfind("</body></html>\n") == html.size() - 15);
}

TEST(BatchReport, WritesTheThreeFilesAndRefusesAFolderNotARun) {
  const fs::path out = makeOutput();
  const BatchReportCounts c = writeBatchReport(out);
  EXPECT_EQ(c.done + c.failed + c.notRun, 4);
  const BatchReportFiles r = buildBatchReport(out);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"summary.csv", r.summaryCsv},
                                   {"stats.csv", r.statsCsv},
                                   {"index.html", r.indexHtml}}) {
    std::ifstream in(out / name, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), text) << name;
  }
  const fs::path empty = test::scratchDir() / "empty";
  fs::create_directories(empty);
  try {
    buildBatchReport(empty);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        empty.string() + ": holds no batch.json: it is not the output folder of `mvw batch run`");
  }
}

}  // namespace
}  // namespace mvw::batch
