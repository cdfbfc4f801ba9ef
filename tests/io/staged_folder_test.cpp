// io::StagedFolder, through which every command's group of outputs appears whole or not at all:
// commit moves the staged entries into place, no commit leaves nothing behind (not even the
// temporary folder), an exception on the way leaves the earlier output as it was, and each
// option keeps the contract its users rely on.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/StagedFolder.h"

namespace mvw {
namespace {

namespace fs = std::filesystem;
using io::StagedFolder;

void put(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The names in `dir`, hidden ones too.
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

TEST(StagedFolder, CommitMovesEveryStagedEntryIntoANewFolder) {
  const fs::path root = test::scratchDir(), out = root / "out";
  {
    StagedFolder staged(out);
    EXPECT_FALSE(fs::exists(out));  // nothing appears before the commit
    EXPECT_EQ(staged.path().parent_path(), root);
    put(staged.path() / "a.txt", "a");
    fs::create_directory(staged.path() / "frames");
    put(staged.path() / "frames" / "0.png", "f");
    staged.commit();
    EXPECT_TRUE(staged.committed());
  }
  EXPECT_EQ(entries(root), std::set<std::string>{"out"});  // the temporary folder is gone
  EXPECT_EQ(entries(out), (std::set<std::string>{"a.txt", "frames"}));
  EXPECT_EQ(read(out / "a.txt"), "a");
  EXPECT_EQ(read(out / "frames" / "0.png"), "f");
}

// What kill -9 leaves (no handler runs): the next StagedFolder of its purpose beside it removes
// it, but never a live process's (locked), one just made (younger than 10 s, before its flock),
// another purpose's, or a name it did not make.
TEST(StagedFolder, AFolderAKilledProcessLeftIsRemovedByTheNextOne) {
  const fs::path root = test::scratchDir();
  const auto aged = [&](const std::string& name) {
    fs::create_directories(root / name / "frames");
    put(root / name / "frames" / "0.png", "f");
    fs::last_write_time(root / name, fs::file_time_type::clock::now() - std::chrono::minutes(5));
    return root / name;
  };
  const fs::path killed = aged(".mvw-staging-999999-0-out");
  const fs::path killedInside = aged(".mvw-staging-999998-3");
  const fs::path live = aged(".mvw-staging-999997-0-out");
  const fs::path otherPurpose = aged(".mvw-render-999999-0-out");
  const fs::path notOurs = aged(".mvw-staging-notapid-0");
  fs::create_directory(root / ".mvw-staging-999996-0-out");  // just made: younger than 10 s
  const int fd = ::open(live.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);  // as its live process holds it
  {
    StagedFolder staged(root / "out");
    EXPECT_FALSE(fs::exists(killed));
    EXPECT_FALSE(fs::exists(killedInside));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(otherPurpose));
    EXPECT_TRUE(fs::exists(notOurs));
    EXPECT_TRUE(fs::exists(root / ".mvw-staging-999996-0-out"));
    // This process's own folder is locked while it lives: another StagedFolder keeps it.
    fs::last_write_time(staged.path(), fs::file_time_type::clock::now() - std::chrono::minutes(5));
    StagedFolder second(root / "other");
    EXPECT_TRUE(fs::exists(staged.path()));
  }
  ::close(fd);
}

TEST(StagedFolder, WithoutACommitNothingIsLeft) {
  const fs::path root = test::scratchDir(), out = root / "out";
  fs::path temporary;
  {
    StagedFolder staged(out);
    temporary = staged.path();
    EXPECT_TRUE(fs::is_directory(temporary));
    EXPECT_EQ(temporary.filename().string().rfind(".mvw-staging-", 0), 0u) << temporary;
    put(temporary / "a.txt", "a");
  }
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_TRUE(entries(root).empty());
}

TEST(StagedFolder, AnExceptionOnTheWayLeavesThePreviousOutputUntouched) {
  const fs::path root = test::scratchDir(), out = root / "out";
  fs::create_directory(out);
  put(out / "a.txt", "old a");
  put(out / "b.txt", "old b");
  EXPECT_THROW(
      {
        StagedFolder staged(out);
        put(staged.path() / "a.txt", "new a");
        throw std::runtime_error("the disk is full");
      },
      std::runtime_error);
  EXPECT_EQ(entries(root), std::set<std::string>{"out"});
  EXPECT_EQ(entries(out), (std::set<std::string>{"a.txt", "b.txt"}));
  EXPECT_EQ(read(out / "a.txt"), "old a");
  EXPECT_EQ(read(out / "b.txt"), "old b");
}

TEST(StagedFolder, MergeReplacesNamesakesAndKeepsTheRest) {
  const fs::path root = test::scratchDir(), out = root / "out";
  fs::create_directories(out / "orbit");
  put(out / "a.txt", "old a");
  put(out / "kept.txt", "kept");
  put(out / "orbit" / "frame-099.png", "an earlier run's frame");
  {
    StagedFolder staged(out);
    put(staged.path() / "a.txt", "new a");
    fs::create_directory(staged.path() / "orbit");
    put(staged.path() / "orbit" / "frame-000.png", "new frame");
    staged.commit();
  }
  EXPECT_EQ(entries(out), (std::set<std::string>{"a.txt", "kept.txt", "orbit"}));
  EXPECT_EQ(read(out / "a.txt"), "new a");
  EXPECT_EQ(read(out / "kept.txt"), "kept");
  // A staged folder replaces its namesake whole.
  EXPECT_EQ(entries(out / "orbit"), std::set<std::string>{"frame-000.png"});
}

TEST(StagedFolder, CommitOfNamesMovesThoseAloneAndDropsTheRest) {
  const fs::path root = test::scratchDir(), out = root / "out";
  {
    StagedFolder staged(out);
    put(staged.path() / "a.txt", "a");
    put(staged.path() / "scratch.txt", "not an output");
    put(staged.path() / "render.json", "{}");
    staged.commit({"a.txt", "render.json"});
  }
  EXPECT_EQ(entries(root), std::set<std::string>{"out"});
  EXPECT_EQ(entries(out), (std::set<std::string>{"a.txt", "render.json"}));
}

TEST(StagedFolder, ANameNotStagedIsRefusedNamingIt) {
  const fs::path root = test::scratchDir(), out = root / "out";
  StagedFolder staged(out);
  try {
    staged.commit({"missing.txt"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.txt"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(staged.committed());
}

TEST(StagedFolder, ReplaceMakesTheDestinationExactlyTheStagedFolder) {
  const fs::path root = test::scratchDir(), out = root / "series";
  fs::create_directory(out);
  put(out / "IM00009.dcm", "an earlier series");
  StagedFolder::Options options;
  options.purpose = "series";
  options.mode = StagedFolder::Mode::Replace;
  {
    StagedFolder staged(out, options);
    EXPECT_EQ(staged.path().filename().string().rfind(".mvw-series-", 0), 0u);
    put(staged.path() / "IM00001.dcm", "new");
    EXPECT_EQ(read(out / "IM00009.dcm"), "an earlier series");  // until the commit
    staged.commit();
  }
  EXPECT_EQ(entries(root), std::set<std::string>{"series"});
  EXPECT_EQ(entries(out), std::set<std::string>{"IM00001.dcm"});
}

TEST(StagedFolder, ReplaceWithoutACommitKeepsTheOldFolder) {
  const fs::path root = test::scratchDir(), out = root / "series";
  fs::create_directory(out);
  put(out / "IM00001.dcm", "old");
  StagedFolder::Options options;
  options.mode = StagedFolder::Mode::Replace;
  {
    StagedFolder staged(out, options);
    put(staged.path() / "IM00001.dcm", "new");
  }
  EXPECT_EQ(entries(root), std::set<std::string>{"series"});
  EXPECT_EQ(read(out / "IM00001.dcm"), "old");
}

TEST(StagedFolder, InsideStagesInTheDestinationAndMovesEverythingOut) {
  const fs::path root = test::scratchDir(), out = root / "download";
  StagedFolder::Options options;
  options.place = StagedFolder::Place::Inside;
  {
    StagedFolder staged(out, options);
    EXPECT_TRUE(fs::is_directory(out));  // made at once: it holds the temporary folder
    EXPECT_EQ(staged.path().parent_path(), out);
    put(staged.path() / "1.2.3.dcm", "x");
    staged.commit();
  }
  EXPECT_EQ(entries(out), std::set<std::string>{"1.2.3.dcm"});
  {
    StagedFolder staged(out, options);
    put(staged.path() / "1.2.4.dcm", "y");
  }
  EXPECT_EQ(entries(out), std::set<std::string>{"1.2.3.dcm"});
}

TEST(StagedFolder, BesideCreatesNoFolderOnTheWayBeforeTheCommit) {
  const fs::path root = test::scratchDir(), out = root / "a" / "b" / "out";
  StagedFolder::Options options;
  options.createNow = false;
  {
    StagedFolder staged(out, options);
    EXPECT_TRUE(entries(root).empty());            // not even the temporary folder yet
    EXPECT_EQ(staged.path().parent_path(), root);  // the nearest folder that exists
    put(staged.path() / "x.png", "x");
  }
  EXPECT_TRUE(entries(root).empty());
  {
    StagedFolder staged(out, options);
    put(staged.path() / "x.png", "x");
    staged.commit();
  }
  EXPECT_EQ(entries(root), std::set<std::string>{"a"});
  EXPECT_EQ(read(out / "x.png"), "x");
}

TEST(StagedFolder, TwoAtOnceNeverShareATemporaryFolder) {
  const fs::path out = test::scratchDir() / "out";
  StagedFolder first(out), second(out);
  EXPECT_NE(first.path(), second.path());
}

TEST(StagedFolder, ADestinationThatIsAFileIsRefused) {
  const fs::path root = test::scratchDir();
  put(root / "afile", "x");
  EXPECT_THROW(StagedFolder(root / "afile"), InputError);
  EXPECT_EQ(entries(root), std::set<std::string>{"afile"});
}

TEST(StagedFolder, APlaceThatCannotBeWrittenIsRefusedAtOnceNamingTheDestination) {
  // /proc takes no new folder, even for root.
  try {
    StagedFolder staged("/proc/mvw-staged-folder-test");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), fs::path("/proc/mvw-staged-folder-test"));
  }
}

}  // namespace
}  // namespace mvw
