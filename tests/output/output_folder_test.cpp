// `mvw render`'s output folder (output::checkOutputFolder): what is refused before anything
// renders. The staging folder the views wait in is io::StagedFolder (staged_folder_test.cpp).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/output/OutputFolder.h"

namespace mvw::output {
namespace {

namespace fs = std::filesystem;

TEST(OutputFolder, AFolderToMakeUnderAWritableFolderIsAccepted) {
  const fs::path dir = test::scratchDir();
  EXPECT_NO_THROW(checkOutputFolder(dir / "new" / "deeper"));
  EXPECT_FALSE(fs::exists(dir / "new"));  // the check makes nothing
}

TEST(OutputFolder, AFileOnTheWayIsNotAFolder) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(checkOutputFolder(dir / "file" / "out"), InputError);
}

TEST(OutputFolder, ANameLongerThanTheFileSystemTakesIsRefused) {
  const fs::path dir = test::scratchDir();
  EXPECT_THROW(checkOutputFolder(dir / std::string(300, 'a')), InputError);
}

}  // namespace
}  // namespace mvw::output
