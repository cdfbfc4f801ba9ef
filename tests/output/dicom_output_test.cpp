// The DICOM output's checks before any work and its --store (output::DicomOutput): a folder that
// is not empty, a server or UID root that cannot be used, and a server that cannot be reached,
// which leaves the objects written and says where.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/output/DicomOutput.h"

namespace mvw::output {
namespace {

namespace fs = std::filesystem;

TEST(DicomOutput, AFolderThatIsNotEmptyTakesDicomObjectsOnlyWithForce) {
  const fs::path dir = test::scratchDir();
  DicomOutputOptions o;
  o.dicom = true;
  EXPECT_NO_THROW(checkDicomDestination(o, dir / "new"));
  EXPECT_NO_THROW(checkDicomDestination(o, dir));  // empty
  std::ofstream(dir / "view.png") << "x";
  try {
    checkDicomDestination(o, dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), dir);
    EXPECT_EQ(e.problem(),
              "exists and is not empty: DICOM objects go into a new or empty folder (give --force "
              "to write into it)");
  }
  o.force = true;
  EXPECT_NO_THROW(checkDicomDestination(o, dir));
  o.force = false;
  EXPECT_NO_THROW(checkDicomDestination(o, {}));  // stats --seg: no folder
  o.dicom = false;
  EXPECT_NO_THROW(checkDicomDestination(o, dir));
}

TEST(DicomOutput, AServerOrUidRootThatCannotBeUsedIsRefusedFirst) {
  DicomOutputOptions o;
  o.store = "no-such-pacs";  // not a URL, and no server of that name is saved
  EXPECT_THROW(checkDicomDestination(o, {}), InputError);
  o.store = "dicom://ORTHANC@127.0.0.1:4242";
  EXPECT_NO_THROW(checkDicomDestination(o, {}));
  o.uidRoot = "1.02.3";  // a leading zero
  try {
    checkDicomDestination(o, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), fs::path("--uid-root"));
  }
  o.uidRoot = "";
  checkDicomDestination(o, {});  // the default root again for the tests after
}

TEST(DicomOutput, WithoutAServerNothingIsSent) {
  const DicomOutputOptions o;
  EXPECT_EQ(storeDicom(o, {"missing.dcm"}, "out", pacs::Options()), std::nullopt);
}

TEST(DicomOutput, AServerThatCannotBeReachedLeavesTheObjectsWrittenAndSaysWhere) {
  DicomOutputOptions o;
  o.store = "http://127.0.0.1:1/dicom-web";  // nothing listens on port 1
  pacs::Options connection;
  connection.connectTimeoutS = 2.0;
  const fs::path file = test::sampleData("pydicom/test_files/CT_small.dcm");
  try {
    storeDicom(o, {file}, "out/folder", connection);
    FAIL() << "no error";
  } catch (const ServiceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("127.0.0.1:1"), std::string::npos) << what;
    const std::string tail =
        " (the DICOM objects stay written in out/folder; send them with mvw pacs store)";
    ASSERT_GE(what.size(), tail.size());
    EXPECT_EQ(what.substr(what.size() - tail.size()), tail) << what;
  }
}

}  // namespace
}  // namespace mvw::output
