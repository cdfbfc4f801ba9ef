// Skip or rerun (batch BatchResume, on BatchInputs' checksums): a study is skipped only when its
// done.json records the same manifest line and input checksums as now; a changed input byte, a
// changed line, a failed or unfinished study runs again.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/batch/BatchInputs.h"
#include "mvw/batch/BatchRecord.h"
#include "mvw/batch/BatchResume.h"
#include "mvw/core/Error.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {
namespace {

namespace fs = std::filesystem;

// A study of a volume file (not a .json config: only the files themselves are its inputs) with
// a label table and a DICOM-like folder as option values.
struct Fixture {
  fs::path dir;
  BatchStudy study;
};

Fixture makeStudy() {
  Fixture f{test::scratchDir(), {}};
  std::ofstream(f.dir / "scan.nii", std::ios::binary) << "volume bytes";
  std::ofstream(f.dir / "labels.txt") << "1 hippocampus\n";
  fs::create_directories(f.dir / "series" / "sub");
  std::ofstream(f.dir / "series" / "1.dcm") << "one";
  std::ofstream(f.dir / "series" / "sub" / "2.dcm") << "two";
  f.study.id = "s1";
  f.study.study = f.dir / "scan.nii";
  f.study.task = "stats";
  f.study.options = {{"labels", (f.dir / "labels.txt").string()},
                     {"series", (f.dir / "series").string()},
                     {"size", "256 256"},
                     {"mip", ""}};
  f.study.line = "s1,scan.nii,stats";
  return f;
}

// OUT/<id>/done.json as a finished run leaves it.
void markDone(const fs::path& folder, const BatchStudy& study,
              const std::map<std::string, std::string>& inputs) {
  fs::create_directories(folder);
  const StudyRun run{&study, folder, inputs, {"stats"}};
  writeRecord(folder / "done.json", doneRecord(run, {"cohort.csv", "0.1.0"}, 1.0));
}

TEST(BatchResume, InputChecksumsCoverTheStudyAndTheFilesItsOptionsName) {
  const Fixture f = makeStudy();
  const auto inputs = batchInputChecksums(f.study);
  ASSERT_EQ(inputs.size(), 3u);  // the study, the label table, the folder; not "256 256" or ""
  EXPECT_EQ(inputs.at((f.dir / "scan.nii").string()), process::fileSha256(f.dir / "scan.nii"));
  EXPECT_EQ(inputs.at((f.dir / "labels.txt").string()), process::fileSha256(f.dir / "labels.txt"));
  EXPECT_EQ(inputs.at((f.dir / "series").string()), process::pathSha256(f.dir / "series"));
  // A study that cannot be read fails with the file named.
  BatchStudy missing = f.study;
  missing.study = f.dir / "gone.nii";
  try {
    batchInputChecksums(missing);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (f.dir / "gone.nii").string() + ": cannot be read (an input of a batch study)");
  }
}

// A study config naming PACS series (what the viewer's Ctrl+S saves): each series is an input by
// its server, study and series, never a path (issue 51: "cannot make absolute path" before).
TEST(BatchResume, APacsSeriesIsAnInputByServerStudyAndSeries) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "ct.nii") << "x";
  std::ofstream(dir / "pacs.json") << R"({"anatomical": {"path": "ct.nii"},
             "functional": {"pacs": "http://pacs:8042/dicom-web", "study": "1.2.3",
                            "series": "4.5.6", "kind": "pet"}})";
  BatchStudy study;
  study.id = "p";
  study.study = dir / "pacs.json";
  study.task = "render";
  study.line = "p,pacs.json,render";
  const auto inputs = batchInputChecksums(study);
  ASSERT_EQ(inputs.size(), 3u);
  const std::string key = pacsInputKey("http://pacs:8042/dicom-web", "1.2.3", "4.5.6");
  EXPECT_EQ(key, "pacs http://pacs:8042/dicom-web study 1.2.3 series 4.5.6");
  ASSERT_EQ(inputs.count(key), 1u);
  EXPECT_EQ(inputs.at(key).size(), 64u);
  EXPECT_EQ(inputs.at((dir / "ct.nii").string()), process::fileSha256(dir / "ct.nii"));
  EXPECT_EQ(pacsInputKey("dicom://ORTHANC@pacs:4242", "1.2", "CT"),
            "pacs dicom://ORTHANC@pacs:4242 study 1.2 series CT");
  // Unchanged without asking the server; another series named: run again.
  const fs::path folder = dir / "out" / "p";
  markDone(folder, study, inputs);
  EXPECT_EQ(decideStudy(folder, study, batchInputChecksums(study)), StudyAction::kSkip);
  std::ofstream(dir / "pacs.json") << R"({"anatomical": {"path": "ct.nii"},
             "functional": {"pacs": "http://pacs:8042/dicom-web", "study": "1.2.3",
                            "series": "4.5.7", "kind": "pet"}})";
  EXPECT_EQ(decideStudy(folder, study, batchInputChecksums(study)), StudyAction::kRun);
}

TEST(BatchResume, SkipsADoneStudyWhoseInputsAndLineAreUnchanged) {
  const Fixture f = makeStudy();
  const fs::path folder = f.dir / "out" / "s1";
  EXPECT_EQ(decideStudy(folder, f.study, batchInputChecksums(f.study)), StudyAction::kRun);
  markDone(folder, f.study, batchInputChecksums(f.study));
  EXPECT_EQ(decideStudy(folder, f.study, batchInputChecksums(f.study)), StudyAction::kSkip);
}

TEST(BatchResume, RerunsWhenAnInputChanges) {
  const Fixture f = makeStudy();
  const fs::path folder = f.dir / "out" / "s1";
  markDone(folder, f.study, batchInputChecksums(f.study));
  std::ofstream(f.dir / "labels.txt") << "1 amygdala\n";  // one byte of an option's file
  EXPECT_EQ(decideStudy(folder, f.study, batchInputChecksums(f.study)), StudyAction::kRun);
  markDone(folder, f.study, batchInputChecksums(f.study));
  std::ofstream(f.dir / "series" / "sub" / "3.dcm") << "three";  // a file more in the series
  EXPECT_EQ(decideStudy(folder, f.study, batchInputChecksums(f.study)), StudyAction::kRun);
  markDone(folder, f.study, batchInputChecksums(f.study));
  std::ofstream(f.dir / "scan.nii", std::ios::binary) << "volume bytez";
  EXPECT_EQ(decideStudy(folder, f.study, batchInputChecksums(f.study)), StudyAction::kRun);
}

TEST(BatchResume, RerunsWhenTheManifestLineChanges) {
  const Fixture f = makeStudy();
  const fs::path folder = f.dir / "out" / "s1";
  const auto inputs = batchInputChecksums(f.study);
  markDone(folder, f.study, inputs);
  BatchStudy changed = f.study;
  changed.line = "s1,scan.nii,stats,--mip";
  EXPECT_EQ(decideStudy(folder, changed, inputs), StudyAction::kRun);
}

TEST(BatchResume, RerunsAFailedUnfinishedOrDamagedStudy) {
  const Fixture f = makeStudy();
  const auto inputs = batchInputChecksums(f.study);
  const fs::path folder = f.dir / "out" / "s1";
  fs::create_directories(folder);
  const StudyRun run{&f.study, folder, inputs, {"stats"}};
  writeRecord(folder / "failed.json", failedRecord(run, {"cohort.csv", "0.1.0"}, 2, "bad", 0.5));
  EXPECT_EQ(decideStudy(folder, f.study, inputs), StudyAction::kRun);
  std::ofstream(folder / "done.json") << "{\"inputs\": ";  // cut off: counts as none
  EXPECT_EQ(decideStudy(folder, f.study, inputs), StudyAction::kRun);
  // The decision on a record as read: null (missing), another study's inputs, no inputs.
  EXPECT_EQ(decideStudy(nlohmann::json(), f.study, inputs), StudyAction::kRun);
  nlohmann::json done = {{"manifest_line", f.study.line}, {"inputs", inputs}};
  EXPECT_EQ(decideStudy(done, f.study, inputs), StudyAction::kSkip);
  done.erase("inputs");
  EXPECT_EQ(decideStudy(done, f.study, inputs), StudyAction::kRun);
  EXPECT_EQ(
      decideStudy(nlohmann::json{{"manifest_line", f.study.line}, {"inputs", {}}}, f.study, inputs),
      StudyAction::kRun);
}

}  // namespace
}  // namespace mvw::batch
