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
std::string refusal(const fs::path& dir, const std::string& name, const std::string& text,
                    const TaskOptions& known = {}) {
  try {
    loadBatchManifest(write(dir / name, text), known);
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
            f + "study 1: \"options\" must be an object of options named without their dashes: "
                "{\"size\": 256, \"mode\": \"mip\"}");
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

// The options of the tasks' commands as the app hands them over (read from their command
// lines): a line giving one its task does not take is refused when the manifest loads, naming
// the line and the option, never left to fail each study's command once the cohort runs.
TaskOptions someTaskOptions() {
  return {{"render", {{"size", {false, 2}}, {"mode", {false, 1}}, {"perspective", {true, 0}}}},
          {"stats", {{"box", {false, 6}}, {"labels", {false, 1}}, {"of", {false, 1}}}},
          {"register", {{"metric-samples", {false, 1}}}}};
}

TEST(BatchManifest, RefusesOptionsTheTaskDoesNotTake) {
  const fs::path dir = cohortDir();
  const TaskOptions known = someTaskOptions();
  const std::string f = (dir / "bad.csv").string() + ": ";
  const std::string header = "id,study,task,size,box,perspective\n";
  // Each option on a line of a task that takes it; an empty cell is no option.
  EXPECT_EQ(refusal(dir, "bad.csv",
                    header + "a,study.json,render,256 128,,true\nb,study.json,stats,,"
                             "-300 -300 -300 300 300 300,\n",
                    known),
            "");
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,sise\na,study.json,render,256\n", known),
            f + "line 2: 'sise' is not an option of mvw render (did you mean 'size'?)");
  EXPECT_EQ(
      refusal(dir, "bad.csv", header + "a,study.json,render,,,\nb,study.json,stats,256,,\n", known),
      f + "line 3: 'size' is not an option of mvw stats (mvw stats --help lists them)");
  EXPECT_EQ(
      refusal(dir, "bad.csv", "id,study,task,options\na,study.json,render,--size 256\n", known),
      f + "line 2: 'options' is not an option of mvw render (a CSV manifest has one column "
          "per option, named as the option without its dashes: size, view, ...; "
          "\"options\" is the JSON manifest's object of them)");
  EXPECT_EQ(refusal(dir, "bad.csv", header + "a,study.json,render,,,yes\n", known),
            f + "line 2: 'perspective' is a flag of mvw render: true, false or empty, not 'yes'");
  EXPECT_EQ(refusal(dir, "bad.csv", header + "a,study.json,render,true,,\n", known),
            f + "line 2: 'size' of mvw render takes a value, not true");
  EXPECT_EQ(refusal(dir, "bad.csv", header + "a,study.json,render,256 --mode mip,,\n", known),
            f + "line 2: the value of 'size' holds '--mode': each option is a column of its own "
                "(or a key of \"options\" in JSON), its cell the value");
  EXPECT_EQ(refusal(dir, "bad.csv",
                    "id,study,task,labels\na,study.json,stats,\"/my data/labels.nii\"\n", known),
            f + "line 2: 'labels' of mvw stats takes one value, not 2 ('/my data/labels.nii': a "
                "value is split at its spaces, quoted or not)");
  EXPECT_EQ(refusal(dir, "bad.csv", header + "a,study.json,render,1 2 3,,\n", known),
            f + "line 2: 'size' of mvw render takes at most 2 values, not 3 ('1 2 3': a value is "
                "split at its spaces, quoted or not)");
  // JSON: the same check, the study named by its place.
  const std::string j = (dir / "bad.json").string() + ": ";
  EXPECT_EQ(refusal(dir, "bad.json",
                    R"([{"id": "a", "study": "study.json", "task": "register",
                         "options": {"metric-sample": 5000}}])",
                    known),
            j + "study 1: 'metric-sample' is not an option of mvw register (did you mean "
                "'metric-samples'?)");
  // Without the table only the names' form is checked (the file format's tests, fuzzing).
  EXPECT_EQ(refusal(dir, "bad.csv", "id,study,task,sise\na,study.json,render,256\n"), "");
}

TEST(BatchManifest, NamesTheTasks) {
  EXPECT_EQ(batchTasks(), (std::vector<std::string>{"render", "stats", "register"}));
}

}  // namespace
}  // namespace mvw::batch
