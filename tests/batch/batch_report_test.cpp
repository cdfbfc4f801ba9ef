// The cohort's records and report (batch BatchRecord, BatchReport): done.json and failed.json as
// a run writes them, and summary.csv, stats.csv and index.html built from an output folder with
// a done render, a failed study, a study not run and a done stats study.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

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
  // Every ROI's name (the count, then the names); the metabolic mean and TLG where stats.json has
  // them (PetStatisticsReachTheTables).
  EXPECT_EQ(r.summaryCsv,
            "id,status,task,seconds,exit_code,message,roi,unit,voxels,volume_ml,max,mean,sd,peak,"
            "metabolic_volume_ml,metabolic_mean,tlg,rois,roi_names\n"
            "a,done,render,1.25,,,,,,,,,,,,,,,\n"
            "b,failed,render,0,2,\"mvw: error: /cohort/b.nii: is <bad> & \"\"odd\"\"\",,,,,,,,,,,,,"
            "\n"
            "c,not run,,,,,,,,,,,,,,,,,\n"
            "d,done,stats,2.5,,,whole,SUV,100,1.5,3,1.25,0.5,2.5,0.75,,,2,"
            "\"whole; hippo, left\"\n");
  EXPECT_EQ(r.statsCsv,
            "id,roi,label,unit,voxels,volume_ml,max,mean,sd,peak,metabolic_volume_ml,"
            "metabolic_mean,tlg\n"
            "d,whole,,SUV,100,1.5,3,1.25,0.5,2.5,0.75,,\n"
            "d,\"hippo, left\",37,SUV,10,0.15,2,1,0.25,1.5,0.05,,\n");
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

// OUT with one PET stats study: its metabolic mean and TLG reach both tables and its page.
TEST(BatchReport, PetStatisticsReachTheTables) {
  const fs::path out = test::scratchDir() / "out";
  fs::create_directories(out / "pet");
  writeBatchIndex(out, "/cohort/cohort.csv", {"pet"});
  const BatchStudy pet = studyOf("pet", "stats");
  std::ofstream(out / "pet" / "stats.json") << R"({"roi": "sphere", "unit": "SUVbw", "voxels": 8,
    "volume_ml": 0.5, "max": 9, "mean": 4, "sd": 1, "peak": 7, "metabolic_volume_ml": 0.25,
    "metabolic_mean": 6.5, "tlg": 1.625})";
  writeRecord(out / "pet" / "done.json",
              doneRecord({&pet, out / "pet", {}, {"stats"}}, kContext, 1.0));
  const BatchReportFiles r = buildBatchReport(out);
  EXPECT_NE(r.summaryCsv.find("\npet,done,stats,1,,,sphere,SUVbw,8,0.5,9,4,1,7,0.25,6.5,1.625,1,"
                              "sphere\n"),
            std::string::npos)
      << r.summaryCsv;
  EXPECT_NE(r.statsCsv.find("\npet,sphere,,SUVbw,8,0.5,9,4,1,7,0.25,6.5,1.625\n"),
            std::string::npos)
      << r.statsCsv;
  EXPECT_NE(r.indexHtml.find("<th>metabolic_mean</th><th>tlg</th></tr>\n<tr><td>sphere</td>"),
            std::string::npos);
  EXPECT_NE(r.indexHtml.find("<td>6.5</td><td>1.625</td></tr>"), std::string::npos);
}

// An orbit shows its first frame (the view's still) and links to its frames and movie.
TEST(BatchReport, AnOrbitShowsItsFirstFrameWithALinkToTheRest) {
  const fs::path out = test::scratchDir() / "out";
  fs::create_directories(out / "o" / "mip");
  writeBatchIndex(out, "/cohort/cohort.csv", {"o"});
  const BatchStudy o = studyOf("o", "render");
  std::ofstream(out / "o" / "mip.png") << "png";
  std::ofstream(out / "o" / "mip.mp4") << "mp4";
  for (const char* f : {"frame-000.png", "frame-001.png", "frame-002.png"})
    std::ofstream(out / "o" / "mip" / f) << "png";
  fs::create_directories(out / "o" / "vr");
  std::ofstream(out / "o" / "vr.png") << "png";
  std::ofstream(out / "o" / "vr" / "frame-000.png") << "png";
  std::ofstream(out / "o" / "render.json") << R"({"views": [{"file": "mip.png", "orbit": {
    "folder": "mip", "movie": "mip.mp4",
    "files": ["mip/frame-000.png", "mip/frame-001.png", "mip/frame-002.png"]}},
    {"file": "vr.png", "orbit": {"folder": "vr", "files": ["vr/frame-000.png"]}}]})";
  writeRecord(out / "o" / "done.json", doneRecord({&o, out / "o", {}, {"render"}}, kContext, 1.0));
  const std::string html = buildBatchReport(out).indexHtml;
  EXPECT_NE(html.find("<img loading=\"lazy\" src=\"o/mip.png\"></a><figcaption>mip · <a "
                      "href=\"o/mip/\">orbit: 3 frames</a> · <a href=\"o/mip.mp4\">movie</a>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<figcaption>vr · <a href=\"o/vr/\">orbit: 1 frame</a></figcaption>"),
            std::string::npos)
      << html;
  EXPECT_EQ(html.find("frame-00"), std::string::npos);
}

// A cohort larger than a page: the index holds the counts, the failures by message, the
// durations and the pages; each page its studies, linked to its neighbours.
TEST(BatchReport, ALargeCohortIsPagedAndItsFailuresGroupedByMessage) {
  const fs::path out = test::scratchDir() / "out";
  std::vector<std::string> ids;
  for (int k = 0; k < 7; ++k) {
    const std::string id = "s" + std::to_string(k);
    ids.push_back(id);
    fs::create_directories(out / id);
    const BatchStudy s = studyOf(id, "render");
    if (k % 2)
      writeRecord(out / id / "failed.json",
                  failedRecord({&s, out / id, {}, {"render"}}, kContext, 2,
                               k == 5 ? "mvw: error: other" : "mvw: error: same", 0.5));
    else
      writeRecord(out / id / "done.json",
                  doneRecord({&s, out / id, {}, {"render"}}, kContext, 3.0 + k));
  }
  writeBatchIndex(out, "/cohort/cohort.csv", ids);
  const BatchReportFiles r = buildBatchReport(out, {3, 1'000'000});
  ASSERT_EQ(r.pages.size(), 3u);
  EXPECT_EQ(r.pages[0].first, "page-0001.html");
  EXPECT_EQ(r.pages[2].first, "page-0003.html");
  const auto has = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  EXPECT_TRUE(
      has(r.indexHtml,
          "<li>2 studies: exit 2: mvw: error: same<br><a href=\"page-0001.html#s1\">s1</a>, "
          "<a href=\"page-0002.html#s3\">s3</a></li>\n"
          "<li><a href=\"page-0002.html#s5\">s5</a>: exit 2: mvw: error: other</li>\n"))
      << r.indexHtml;
  EXPECT_TRUE(has(r.indexHtml, "<tr><td>&lt; 1 s</td><td>3</td>"));
  EXPECT_TRUE(has(r.indexHtml, "<tr><td>2-5 s</td><td>1</td>"));
  EXPECT_TRUE(has(r.indexHtml, "<tr><td>5-10 s</td><td>3</td>"));
  EXPECT_TRUE(has(r.indexHtml,
                  "<li><a href=\"page-0003.html\">s6 … s6</a>: 1 done, 0 failed, "
                  "0 not run</li>"));
  EXPECT_FALSE(has(r.indexHtml, "<section"));
  EXPECT_TRUE(has(r.pages[1].second,
                  "<a href=\"index.html\">index</a> · <a "
                  "href=\"page-0001.html\">previous</a> · <a "
                  "href=\"page-0003.html\">next</a>"));
  EXPECT_TRUE(has(r.pages[1].second, "<section id=\"s3\""));
  EXPECT_FALSE(has(r.pages[2].second, "next</a>"));
  // Written: the pages beside index.html; a smaller report later removes them.
  writeBatchReport(out, {3, 1'000'000});
  EXPECT_TRUE(fs::exists(out / "page-0003.html"));
  writeBatchReport(out);
  EXPECT_FALSE(fs::exists(out / "page-0001.html"));
  EXPECT_TRUE(has(buildBatchReport(out).indexHtml, "<section id=\"s6\""));
}

}  // namespace
}  // namespace mvw::batch
