// Cohort manifests (batch BatchManifest): CSV and JSON read into studies with absolute paths and
// their option columns, and every bad manifest refused with the one message that names the file
// and the line.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/batch/BatchManifest.h"
#include "mvw/core/Error.h"

namespace mvw::batch {
namespace {

namespace fs = std::filesystem;

// A scratch folder with a study config (its bytes are not read here) and a label table.
fs::path cohortDir() {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "study.json") << "{}\n";
  std::ofstream(dir / "labels.txt") << "1 a\n";
  return dir;
}

fs::path write(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

// The message loading `text` as `name` in `dir` throws, "" when it loads.
std::string refusal(const fs::path& dir, const std::string& name, const std::string& text) {
  try {
    loadBatchManifest(write(dir / name, text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BatchManifest, ReadsCsvRowsOptionsAndPaths) {
  const fs::path dir = cohortDir();
  const fs::path file = write(dir / "cohort.csv",
                              "# a comment, then the header\r\n"
                              "id,study,task,size,labels,mip,annotate\r\n"
                              "\n"
                              "a,study.json,render,256 256,,true,false\n"
                              "b, \"" +
                                  (dir / "study.json").string() + "\",stats,,labels.txt,,\n");
  const BatchManifest m = loadBatchManifest(file);
  EXPECT_EQ(m.file, file);
  ASSERT_EQ(m.studies.size(), 2u);
  const BatchStudy& a = m.studies[0];
  EXPECT_EQ(a.id, "a");
  EXPECT_EQ(a.task, "render");
  EXPECT_EQ(a.study, dir / "study.json");
  EXPECT_EQ(a.studyText, "study.json");
  EXPECT_EQ(a.line, "a,study.json,render,256 256,,true,false");
  EXPECT_EQ(a.lineNumber, 4);
  // "true" is a flag, "false" and "" leave the option out.
  using Options = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(a.options, (Options{{"size", "256 256"}, {"mip", ""}}));
  const BatchStudy& b = m.studies[1];
  EXPECT_EQ(b.study, dir / "study.json");
  EXPECT_EQ(b.lineNumber, 5);
  // A relative file an option names is made absolute, as the study column is.
  EXPECT_EQ(b.options, (Options{{"labels", (dir / "labels.txt").string()}}));
}

TEST(BatchManifest, ReadsJsonStudiesAndOptionTypes) {
  const fs::path dir = cohortDir();
  const fs::path file = write(dir / "cohort.JSON", R"({"studies": [
    {"id": "a", "study": "study.json", "task": "render",
     "options": {"size": [128, 96], "mip": true, "annotate": false, "label": 37, "of": "anatomical"}},
    {"task": "stats", "id": "b", "study": "study.json"}]})");
  const BatchManifest m = loadBatchManifest(file);
  ASSERT_EQ(m.studies.size(), 2u);
  using Options = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(m.studies[0].options,
            (Options{{"label", "37"}, {"mip", ""}, {"of", "anatomical"}, {"size", "128 96"}}));
  EXPECT_EQ(m.studies[0].lineNumber, 1);
  EXPECT_EQ(m.studies[1].id, "b");
  EXPECT_EQ(m.studies[1].study, dir / "study.json");
  EXPECT_EQ(m.studies[1].line, R"({"id":"b","study":"study.json","task":"stats"})");
  // A bare list is a manifest too.
  EXPECT_EQ(loadBatchManifest(write(dir / "list.json",
                                    R"([{"id": "x", "study": "study.json", "task": "stats"}])"))
                .studies.size(),
            1u);
}

TEST(BatchManifest, RefusesBadCsvNamingTheFileAndLine) {
  const fs::path dir = cohortDir();
  const std::string f = (dir / "bad.csv").string() + ": ";
  const std::string ok = "id,study,task\na,study.json,render\n";
  EXPECT_EQ(refusal(dir, "bad.csv", ok), "");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\na,study.json,render\nb,study.json,paint\n"),
            f + "line 3: unknown task 'paint' (render, stats or register)");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\na,nope.json,render\n"),
            f + "line 2: the study config " + (dir / "nope.json").string() +
                ": no such file or directory");
  EXPECT_EQ(refusal(dir, "bad.csv",
                    "id,study,task\na,study.json,render\n# a comment\na,study.json,stats\n"),
            f + "line 4: the id 'a' is already used on line 2");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,size\na,study.json\n"),
            f + "line 2: 2 fields, the header has 4");
  EXPECT_EQ(refusal(dir, "bad.csv", "study,id,task\n"),
            f + "line 1: the header must start with id,study,task (it is 'study,id,task')");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\n../x,study.json,render\n"),
            f + "line 2: the id '../x' starts with '.' (ids are folder names)");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\na/b,study.json,render\n"),
            f + "line 2: the id 'a/b' has '/': ids are folder names of letters, digits, '-', '_' "
                "and '.'");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\n\"\",study.json,render\n"),
            f + "line 2: the id is empty");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\na,,render\n"),
            f + "line 2: the study column is empty");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,--size\n"),
            f + "line 1: the option column '--size' starts with '-': leave the dashes out");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,Size\n"),
            f + "line 1: the option column 'Size' is not an option name (lower-case letters, "
                "digits and '-', without the leading dashes)");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,output\n"),
            f + "line 1: the option column 'output' is set by mvw batch itself");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,size,size\n"),
            f + "line 1: the column 'size' is there twice");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task\na,\"study.json,render\n"),
            f + "line 2: a quote is not closed");
  EXPECT_EQ(refusal(dir, "bad.csv", ""), f + "is empty: no header id,study,task");
  EXPECT_EQ(refusal(dir, "bad.csv", "# only a comment\nid,study,task\n"), f + "lists no study");
  EXPECT_THROW(loadBatchManifest(dir / "none.csv"), InputError);
}

TEST(BatchManifest, RefusesBadJsonNamingTheStudy) {
  const fs::path dir = cohortDir();
  const std::string f = (dir / "bad.json").string() + ": ";
  EXPECT_EQ(refusal(dir, "bad.json",
                    R"({"studies": [{"id": "a", "study": "study.json", "task": "render",
                        "colour": 1}]})"),
            f + "study 1: unknown key 'colour' (id, study, task, options)");
  EXPECT_EQ(refusal(dir, "bad.json", R"({"studies": [], "version": 2})"),
            f + "unknown key 'version' (only \"studies\")");
  EXPECT_EQ(refusal(dir, "bad.json", R"({})"), f + "has no \"studies\" list");
  EXPECT_EQ(refusal(dir, "bad.json", R"({"studies": {}})"),
            f + "\"studies\" must be a list of objects");
  EXPECT_EQ(
      refusal(dir, "bad.json", R"([{"id": "a", "study": "study.json", "task": "render"}, 3])"),
      f + "study 2: not an object");
  EXPECT_EQ(refusal(dir, "bad.json", R"([{"id": 7, "study": "study.json", "task": "render"}])"),
            f + "study 1: \"id\" must be a string");
  EXPECT_EQ(refusal(dir, "bad.json",
                    R"([{"id": "a", "study": "study.json", "task": "render", "options": []}])"),
            f + "study 1: \"options\" must be an object");
  EXPECT_EQ(refusal(dir, "bad.json",
                    R"([{"id": "a", "study": "study.json", "task": "render",
                         "options": {"size": [1, {}]}}])"),
            f + "study 1: option 'size': a list of numbers or strings");
  EXPECT_EQ(refusal(dir, "bad.json",
                    R"([{"id": "a", "study": "study.json", "task": "render",
                         "options": {"size": null}}])"),
            f + "study 1: option 'size' must be a string, number, list or true/false");
  EXPECT_EQ(refusal(dir, "bad.json", "[]"), f + "lists no study");
  EXPECT_EQ(refusal(dir, "bad.json", "{").rfind(f + "is not valid JSON: ", 0), 0u);
}

TEST(BatchManifest, NamesTheTasks) {
  EXPECT_EQ(batchTasks(), (std::vector<std::string>{"render", "stats", "register"}));
}

}  // namespace
}  // namespace mvw::batch
