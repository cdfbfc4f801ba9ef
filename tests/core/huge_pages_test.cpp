// The second start for transparent huge pages (mvw/core/HugePages.h), without starting again:
// the second start puts GLIBC_TUNABLES back as the user had it, and a run not worth a second
// start or a user's own hugetlb setting leaves the environment as it is.
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mvw/core/HugePages.h"

namespace mvw {
namespace {

std::optional<std::string> env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::optional<std::string>(v) : std::nullopt;
}

// The environment variables this test changes, put back when it ends.
class HugePages : public ::testing::Test {
 protected:
  void TearDown() override {
    for (const auto& [name, value] :
         {std::pair{"GLIBC_TUNABLES", tunables_}, std::pair{kHugePagesMark, mark_}})
      if (value)
        setenv(name, value->c_str(), 1);
      else
        unsetenv(name);
  }
  char* argv_[3] = {const_cast<char*>("mvw"), const_cast<char*>("info"), nullptr};

 private:
  std::optional<std::string> tunables_ = env("GLIBC_TUNABLES"), mark_ = env(kHugePagesMark);
};

TEST_F(HugePages, TheSecondStartPutsTheUsersTunablesBack) {
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1);
  setenv(kHugePagesMark, "glibc.malloc.check=3", 1);
  restartWithHugePages(argv_, true);
  EXPECT_EQ(env("GLIBC_TUNABLES"), "glibc.malloc.check=3");
  EXPECT_EQ(env(kHugePagesMark), std::nullopt);
}

TEST_F(HugePages, TheSecondStartUnsetsTunablesTheUserHadNot) {
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1);
  setenv(kHugePagesMark, "-", 1);
  restartWithHugePages(argv_, false);  // the second start, whatever the command
  EXPECT_EQ(env("GLIBC_TUNABLES"), std::nullopt);
  EXPECT_EQ(env(kHugePagesMark), std::nullopt);
}

TEST_F(HugePages, NoSecondStartWhenNotWorthIt) {
  unsetenv(kHugePagesMark);
  setenv("GLIBC_TUNABLES", "glibc.malloc.check=3", 1);
  restartWithHugePages(argv_, false);  // returns: no exec
  EXPECT_EQ(env("GLIBC_TUNABLES"), "glibc.malloc.check=3");
  EXPECT_EQ(env(kHugePagesMark), std::nullopt);
}

TEST_F(HugePages, AUsersOwnHugetlbSettingIsKept) {
  unsetenv(kHugePagesMark);
  setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1);
  restartWithHugePages(argv_, true);  // returns: no exec
  EXPECT_EQ(env("GLIBC_TUNABLES"), "glibc.malloc.hugetlb=0");
  EXPECT_EQ(env(kHugePagesMark), std::nullopt);
}

bool readsVolumes(std::vector<const char*> args) {
  args.insert(args.begin(), "mvw");
  args.push_back(nullptr);
  return commandReadsVolumes(const_cast<char**>(args.data()));
}

TEST(CommandReadsVolumes, OnlyCommandsThatReadVolumesAreWorthASecondStart) {
  EXPECT_TRUE(readsVolumes({"info", "ct.nii.gz"}));
  EXPECT_TRUE(readsVolumes({"render", "study.json", "-o", "out"}));
  EXPECT_FALSE(readsVolumes({"pacs", "find", "clinic"}));
  EXPECT_FALSE(readsVolumes({"config", "reference"}));
  EXPECT_FALSE(readsVolumes({}));
  EXPECT_FALSE(readsVolumes({"--version"}));
  EXPECT_FALSE(readsVolumes({"--help"}));
}

TEST(CommandReadsVolumes, TheGlobalOptionsValuesAreNotCommands) {
  EXPECT_FALSE(readsVolumes({"--cache", "info", "pacs", "find", "x"}));
  EXPECT_TRUE(readsVolumes({"--connect-timeout", "pacs", "stats", "pet.nii.gz"}));
  EXPECT_FALSE(readsVolumes({"--read-timeout", "5", "config"}));
  EXPECT_TRUE(readsVolumes({"--read-timeout=5", "view"}));
  EXPECT_FALSE(readsVolumes({"--cache"}));  // the value missing: no command
}

}  // namespace
}  // namespace mvw
