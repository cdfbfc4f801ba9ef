// The input hashes a rerun reuses (batch BatchHashCache): a file's SHA-256 is reused only while
// its size, modification time and inode are unchanged; a same-size rewrite with a new mtime is
// hashed again and reruns the study (BatchResume); --verify trusts nothing remembered; a file
// modified just before it was hashed is not remembered.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/batch/BatchHashCache.h"
#include "mvw/batch/BatchInputs.h"
#include "mvw/batch/BatchRecord.h"
#include "mvw/batch/BatchResume.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// Writes `text` in place (the inode stays) and sets the mtime `ago` in the past.
void write(const fs::path& file, const std::string& text, fs::file_time_type::duration ago) {
  std::ofstream(file, std::ios::binary | std::ios::in | std::ios::out | std::ios::trunc) << text;
  fs::last_write_time(file, fs::file_time_type::clock::now() - ago);
}

TEST(BatchHashCache, AnUnchangedStatReusesTheHashAChangedOneHashesAgain) {
  const fs::path dir = test::scratchDir();
  const fs::path file = dir / "scan.nii";
  write(file, "volume AAAA", 100s);
  const auto mtime = fs::last_write_time(file);
  {
    BatchHashCache cache(dir / "hashes", "all.tsv", false);
    EXPECT_EQ(cache.pathSha256(file, "r"), process::fileSha256(file));
    EXPECT_EQ(cache.hashed(), 1);
    cache.save();
  }
  // The same size and the same mtime: the remembered hash, though the bytes differ (the cache's
  // premise, as DVC's; --verify is the way out).
  write(file, "volume BBBB", 0s);
  fs::last_write_time(file, mtime);
  {
    BatchHashCache cache(dir / "hashes", "all.tsv", false);
    EXPECT_NE(cache.pathSha256(file, "r"), process::fileSha256(file));
    EXPECT_EQ(cache.reused(), 1);
    EXPECT_EQ(cache.hashed(), 0);
    BatchHashCache verify(dir / "hashes", "all.tsv", true);
    EXPECT_EQ(verify.pathSha256(file, "r"), process::fileSha256(file));
    EXPECT_EQ(verify.hashed(), 1);
  }
  // The same size, a new mtime: hashed again.
  write(file, "volume CCCC", 50s);
  {
    BatchHashCache cache(dir / "hashes", "all.tsv", false);
    EXPECT_EQ(cache.pathSha256(file, "r"), process::fileSha256(file));
    EXPECT_EQ(cache.hashed(), 1);
  }
}

TEST(BatchHashCache, AFolderIsReusedWhileEveryFileInItKeepsItsStat) {
  const fs::path dir = test::scratchDir();
  fs::create_directories(dir / "series" / "sub");
  write(dir / "series" / "1.dcm", "one", 100s);
  write(dir / "series" / "sub" / "2.dcm", "two", 100s);
  {
    BatchHashCache cache(dir / "hashes", "all.tsv", false);
    EXPECT_EQ(cache.pathSha256(dir / "series", "r"), process::pathSha256(dir / "series"));
    cache.save();
  }
  {
    BatchHashCache cache(dir / "hashes", "all.tsv", false);
    EXPECT_EQ(cache.pathSha256(dir / "series", "r"), process::pathSha256(dir / "series"));
    EXPECT_EQ(cache.reused(), 1);
  }
  write(dir / "series" / "sub" / "2.dcm", "TWO", 50s);
  {
    BatchHashCache cache(dir / "hashes", "all.tsv", false);
    EXPECT_EQ(cache.pathSha256(dir / "series", "r"), process::pathSha256(dir / "series"));
    EXPECT_EQ(cache.hashed(), 1);
  }
}

TEST(BatchHashCache, AFileModifiedJustBeforeItWasHashedIsNotRemembered) {
  const fs::path dir = test::scratchDir();
  write(dir / "fresh.nii", "fresh", 0s);
  write(dir / "old.nii", "old", 100s);
  BatchHashCache cache(dir / "hashes", "shard-1-of-4.tsv", false);
  cache.pathSha256(dir / "fresh.nii", "r");
  cache.pathSha256(dir / "old.nii", "r");
  cache.save();
  std::ifstream in(dir / "hashes" / "shard-1-of-4.tsv");
  std::string text(std::istreambuf_iterator<char>(in), {});
  EXPECT_EQ(text.find("fresh.nii"), std::string::npos) << text;
  EXPECT_NE(text.find(process::fileSha256(dir / "old.nii") + "\tf:3:"), std::string::npos) << text;
  // Every shard's file is read.
  BatchHashCache other(dir / "hashes", "shard-2-of-4.tsv", false);
  other.pathSha256(dir / "old.nii", "r");
  EXPECT_EQ(other.reused(), 1);
}

TEST(BatchHashCache, ASameSizeRewriteWithANewMtimeRerunsTheStudy) {
  const fs::path dir = test::scratchDir();
  write(dir / "scan.nii", "volume AAAA", 100s);
  BatchStudy study;
  study.id = "s1";
  study.study = dir / "scan.nii";
  study.task = "stats";
  study.line = "s1,scan.nii,stats";
  BatchHashCache first(dir / "hashes", "all.tsv", false);
  const auto inputs = batchInputChecksums(study, &first);
  first.save();
  fs::create_directories(dir / "s1");
  writeRecord(dir / "s1" / "done.json",
              doneRecord({&study, dir / "s1", inputs, {"stats"}}, {"cohort.csv", "0.1.0"}, 1.0));
  BatchHashCache again(dir / "hashes", "all.tsv", false);
  EXPECT_EQ(decideStudy(dir / "s1", study, batchInputChecksums(study, &again)), StudyAction::kSkip);
  EXPECT_EQ(again.reused(), 1);
  write(dir / "scan.nii", "volume BBBB", 50s);
  BatchHashCache changed(dir / "hashes", "all.tsv", false);
  EXPECT_EQ(decideStudy(dir / "s1", study, batchInputChecksums(study, &changed)),
            StudyAction::kRun);
  EXPECT_EQ(changed.hashed(), 1);
}

}  // namespace
}  // namespace mvw::batch
