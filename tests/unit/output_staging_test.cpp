// `mvw render`'s output folder (output::Staging, checkOutputFolder): what is refused before
// anything renders, and a staging folder that is made only when used and leaves nothing behind.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/output/Staging.h"

namespace mvw::output {
namespace {

namespace fs = std::filesystem;

TEST(OutputStaging, AFolderToMakeUnderAWritableFolderIsAccepted) {
  const fs::path dir = test::scratchDir();
  EXPECT_NO_THROW(checkOutputFolder(dir / "new" / "deeper"));
  EXPECT_FALSE(fs::exists(dir / "new"));  // the check makes nothing
}

TEST(OutputStaging, AFileOnTheWayIsNotAFolder) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(checkOutputFolder(dir / "file" / "out"), InputError);
}

TEST(OutputStaging, ANameLongerThanTheFileSystemTakesIsRefused) {
  const fs::path dir = test::scratchDir();
  EXPECT_THROW(checkOutputFolder(dir / std::string(300, 'a')), InputError);
}

TEST(OutputStaging, MadeOnFirstUseBesideTheOutputAndRemovedWithItsFiles) {
  const fs::path dir = test::scratchDir();
  fs::path staged;
  {
    Staging staging(dir / "out");
    EXPECT_TRUE(fs::is_empty(dir));  // nothing until a file needs it
    staged = staging.dir();
    EXPECT_EQ(staged.parent_path(), fs::absolute(dir).lexically_normal());
    EXPECT_TRUE(fs::is_directory(staged));
    std::ofstream(staged / "view.png") << "x";
  }
  EXPECT_FALSE(fs::exists(staged));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace mvw::output
