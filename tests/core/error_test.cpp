// Error (core): whyUnreadable and requireReadable say what is wrong with a path (absent, a
// folder, a dangling or looping link), as every InputError about an unreadable file does.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"

TEST(Error, WhyUnreadableSaysWhatThePathIs) {
  namespace fs = std::filesystem;
  const fs::path dir = mvw::test::scratchDir() / "why-unreadable";
  fs::remove_all(dir);
  fs::create_directories(dir / "folder");
  std::ofstream(dir / "file.json") << "{}";
  fs::create_symlink(dir / "gone", dir / "dangling");
  fs::create_symlink(dir / "loop-b", dir / "loop-a");
  fs::create_symlink(dir / "loop-a", dir / "loop-b");
  EXPECT_EQ(mvw::whyUnreadable(dir / "file.json"), "");
  EXPECT_EQ(mvw::whyUnreadable(dir / "absent"), "no such file or directory");
  EXPECT_EQ(mvw::whyUnreadable(dir / "folder"), "is a folder, not a file");
  EXPECT_NE(mvw::whyUnreadable(dir / "dangling").find("symbolic link that leads to nothing"),
            std::string::npos);
  EXPECT_NE(mvw::whyUnreadable(dir / "loop-a").find("symbolic link that leads to nothing"),
            std::string::npos);
  EXPECT_EQ(mvw::whyUnreadable(dir / "file.json" / "below"), "cannot be read: Not a directory");
  try {
    mvw::requireReadable(dir / "folder");
    FAIL() << "no error";
  } catch (const mvw::InputError& e) {
    EXPECT_EQ(e.file(), dir / "folder");
    EXPECT_EQ(e.problem(), "is a folder, not a file");
  }
}
