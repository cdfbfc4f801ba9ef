// What `mvw pacs store` sends (pacs::storeFiles, issue 51 item 6): a folder's DICOM files, its
// other files (a render's PNGs and render.json) listed as skipped; a file named that is not
// DICOM, or a folder without DICOM, refused naming it.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/pacs/StoreFiles.h"

namespace mvw::pacs {
namespace {

namespace fs = std::filesystem;

// The first two files of the Cranium CT: real DICOM instances.
std::vector<fs::path> twoInstances() {
  std::vector<fs::path> all;
  for (const auto& e : fs::directory_iterator(test::sampleData("cranium/dicom")))
    all.push_back(e.path());
  std::sort(all.begin(), all.end());
  return {all.at(0), all.at(1)};
}

std::string refusal(const std::vector<fs::path>& inputs) {
  try {
    storeFiles(inputs);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(StoreFiles, AFolderSendsItsDicomFilesAndSkipsTheRest) {
  const fs::path dir = test::scratchDir() / "render";
  fs::create_directories(dir / "bone");
  const std::vector<fs::path> dicom = twoInstances();
  fs::copy_file(dicom[0], dir / "mip.dcm");
  fs::copy_file(dicom[1], dir / "bone" / "orbit.dcm");
  std::ofstream(dir / "mip.png") << "\x89PNG";
  std::ofstream(dir / "render.json") << "{}";
  std::ofstream(dir / "bone" / "frame-000.png") << "\x89PNG";
  const StoreFiles chosen = storeFiles({dir});
  EXPECT_EQ(chosen.files, (std::vector<fs::path>{dir / "bone" / "orbit.dcm", dir / "mip.dcm"}));
  EXPECT_EQ(chosen.skipped, (std::vector<fs::path>{dir / "bone" / "frame-000.png", dir / "mip.png",
                                                   dir / "render.json"}));
  EXPECT_EQ(chosen.bytes, fs::file_size(dicom[0]) + fs::file_size(dicom[1]));
  // A file named on its own is meant: DICOM goes, anything else is refused.
  EXPECT_EQ(storeFiles({dir / "mip.dcm"}).files, std::vector<fs::path>{dir / "mip.dcm"});
  EXPECT_EQ(refusal({dir / "mip.dcm", dir / "mip.png"}),
            (dir / "mip.png").string() + ": is not a DICOM file with a SOP Instance UID");
  // A folder holding no DICOM at all is refused too.
  fs::remove(dir / "mip.dcm");
  fs::remove(dir / "bone" / "orbit.dcm");
  EXPECT_EQ(refusal({dir}), dir.string() + ": holds no DICOM files to store");
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_EQ(refusal({dir}), dir.string() + ": holds no files to store");
}

}  // namespace
}  // namespace mvw::pacs
