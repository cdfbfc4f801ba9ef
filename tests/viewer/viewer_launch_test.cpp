// What `mvw view` opens (mvw/viewer/ViewerLaunch.h), decided before any window: the servers of
// --servers or of the default file (a bad default is a problem shown, not bad input), a study
// from volumes on the command line, or nothing but the PACS window.
#include "mvw/viewer/ViewerLaunch.h"

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "ViewerTestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeWriter.h"

namespace mvw::viewer {
namespace {

namespace fs = std::filesystem;

// XDG_CONFIG_HOME (where the default servers.json is) set to a scratch folder for one test.
class ViewerLaunchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("XDG_CONFIG_HOME")) saved_ = v;
    dir_ = test::scratchDir();
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
  }
  void TearDown() override {
    if (saved_)
      setenv("XDG_CONFIG_HOME", saved_->c_str(), 1);
    else
      unsetenv("XDG_CONFIG_HOME");
  }
  fs::path write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  fs::path dir_;
  std::optional<std::string> saved_;
};

const char* kOneServer =
    R"({"servers": [{"name": "clinic", "url": "dicom://PACS@127.0.0.1:4242"}]})";

TEST_F(ViewerLaunchTest, ServersAloneOpenThePacsWindow) {
  write(dir_ / "mvw" / "servers.json", kOneServer);
  const ViewerLaunch v = launchViewer({}, {});
  EXPECT_EQ(v.serversFile, dir_ / "mvw" / "servers.json");
  ASSERT_EQ(v.servers.size(), 1u);
  EXPECT_EQ(v.servers[0].name, "clinic");
  EXPECT_TRUE(v.serversProblem.empty());
  EXPECT_EQ(v.session, nullptr);
}

TEST_F(ViewerLaunchTest, GivenServersFileWins) {
  write(dir_ / "mvw" / "servers.json", "not json");
  const fs::path given = write(dir_ / "other.json", kOneServer);
  ViewerLaunchOptions o;
  o.servers = given.string();
  const ViewerLaunch v = launchViewer(o, {});
  EXPECT_EQ(v.serversFile, given);
  EXPECT_EQ(v.servers.size(), 1u);
}

TEST_F(ViewerLaunchTest, ABadGivenServersFileIsBadInput) {
  ViewerLaunchOptions o;
  o.servers = write(dir_ / "bad.json", "not json").string();
  EXPECT_THROW(launchViewer(o, {}), InputError);
}

TEST_F(ViewerLaunchTest, NothingToOpenIsBadInputNamingTheServersFile) {
  try {
    launchViewer({}, {});
    FAIL() << "no study and no servers opened a window";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("give a study config or --anatomical"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find((dir_ / "mvw" / "servers.json").string()),
              std::string::npos);
  }
}

TEST_F(ViewerLaunchTest, ABadDefaultServersFileIsAProblemShown) {
  write(dir_ / "mvw" / "servers.json", "not json");
  const fs::path ct = dir_ / "ct.nii.gz";
  io::writeVolume(makeVolume("CT", -1000.0, 2000.0), ct);
  ViewerLaunchOptions o;
  o.anatomical = ct.string();
  const ViewerLaunch v = launchViewer(o, {});
  EXPECT_FALSE(v.serversProblem.empty());
  EXPECT_TRUE(v.servers.empty());
  ASSERT_NE(v.session, nullptr);
  EXPECT_EQ(v.session->anatomical().dimensions(), glm::ivec3(9, 7, 5));
  EXPECT_EQ(v.session->functional(), nullptr);
}

TEST_F(ViewerLaunchTest, VolumesMakeAStudy) {
  const fs::path ct = dir_ / "ct.nii.gz", pet = dir_ / "pet.nii.gz";
  io::writeVolume(makeVolume("CT", -1000.0, 2000.0), ct);
  io::writeVolume(makeVolume("PT", 0.0, 10.0), pet);
  ViewerLaunchOptions o;
  o.anatomical = ct.string();
  o.functional = pet.string();
  const ViewerLaunch v = launchViewer(o, {});
  ASSERT_NE(v.session, nullptr);
  EXPECT_EQ(v.session->config().anatomical.path, ct);
  ASSERT_TRUE(v.session->config().functional);
  EXPECT_EQ(v.session->config().functional->path, pet);
  EXPECT_NE(v.session->functional(), nullptr);
}

}  // namespace
}  // namespace mvw::viewer
