// servers.json through its field table: read strictly with messages naming the file and the
// key, written so it reads back, and resolveServer, the one place a SERVER argument (`mvw
// pacs`, --store, a study config's "pacs") becomes a server: a URL as it is, else a saved name.
#include "mvw/config/ServerList.h"
#include "mvw/config/StudyConfig.h"

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"

namespace mvw::config {
namespace {

// `text` as the file `name` in `dir` (test::scratchDir() empties the folder it names: a test
// takes it once).
std::filesystem::path write(const std::filesystem::path& dir, const std::string& name,
                            const std::string& text) {
  const std::filesystem::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

// readServerList's problem for `text`, with the file named; "" when it reads.
std::string problemIn(const std::string& text) {
  const std::filesystem::path file = write(test::scratchDir(), "servers.json", text);
  try {
    readServerList(file);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    return e.problem();
  }
  return "";
}

const char* kServers =
    R"({"servers": [{"name": "clinic", "url": "dicom://ORTHANC@127.0.0.1:4242",
                     "calling_aet": "VIEWER"},
                    {"name": "Research PACS", "url": "http://127.0.0.1:1/dicom-web"}]})";

TEST(ServerList, ReadsEachKeyAndTheDefaultCallingAet) {
  const auto servers = readServerList(write(test::scratchDir(), "servers.json", kServers));
  ASSERT_EQ(servers.size(), 2u);
  EXPECT_EQ(servers[0].name, "clinic");
  EXPECT_EQ(servers[0].url, "dicom://ORTHANC@127.0.0.1:4242");
  EXPECT_EQ(servers[0].callingAet, "VIEWER");
  EXPECT_EQ(servers[1].callingAet, "MVW");
}

TEST(ServerList, RefusesABadListNamingTheKey) {
  EXPECT_NE(problemIn(R"({})").find("missing key 'servers'"), std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": 1})").find("'servers' must be an array"), std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": [{"name": "a", "url": "http://h:1/x", "aet": "X"}]})")
                .find("unknown key 'servers[0].aet' (known here: calling_aet, name, url)"),
            std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": [{"name": "a@b", "url": "http://h:1/x"}]})")
                .find("'servers[0].name' must not hold"),
            std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": [{"name": "a"}]})").find("'servers[0]' has no \"url\""),
            std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": [{"name": "a", "url": "ftp://h/x"}]})")
                .find("'servers[0].url' is not a server"),
            std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": [{"name": "a", "url": "http://h:1/x", "token": "t"}]})")
                .find("'servers[0].token' is not accepted: credentials do not belong"),
            std::string::npos);
  EXPECT_NE(problemIn(R"({"servers": [{"name": "a", "url": "http://h:1/x"},
                                      {"name": "a", "url": "http://h:2/x"}]})")
                .find("'servers[1]' repeats the name 'a'"),
            std::string::npos);
}

TEST(ServerList, WritesWhatItReadsBack) {
  const std::filesystem::path file = test::scratchDir() / "new" / "servers.json";
  const std::vector<SavedServer> servers = {{"clinic", "dicom://PACS@10.0.0.2:104", "WS1"},
                                            {"web", "https://pacs.example.org/dicom-web", "MVW"}};
  writeServerList(file, servers);
  const auto back = readServerList(file);
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].name, servers[i].name);
    EXPECT_EQ(back[i].url, servers[i].url);
    EXPECT_EQ(back[i].callingAet, servers[i].callingAet);
  }
}

TEST(ServerList, TheReferenceListsItsKeys) {
  std::vector<std::string> keys;
  for (const ConfigKeyDoc& k : serverListKeyDocs()) keys.push_back(k.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"servers", "servers[].name", "servers[].url",
                                            "servers[].calling_aet"}));
  EXPECT_NE(studyConfigReference().find("| `servers[].calling_aet` |"), std::string::npos);
}

TEST(ServerList, ResolvesAUrlAsItIsAndANameThroughTheList) {
  const std::filesystem::path file = write(test::scratchDir(), "servers.json", kServers);
  EXPECT_EQ(resolveServer("http://pacs:8042/dicom-web", file).baseUrl,
            "http://pacs:8042/dicom-web");
  const pacs::Server clinic = resolveServer("clinic", file);
  EXPECT_EQ(clinic.protocol, pacs::Protocol::Dimse);
  EXPECT_EQ(clinic.calledAet, "ORTHANC");
  EXPECT_EQ(clinic.port, 4242);
  EXPECT_EQ(resolveServer("Research PACS", file).baseUrl, "http://127.0.0.1:1/dicom-web");
  // A URL is never looked up: a bad one is the URL's problem, not an unknown name.
  EXPECT_THROW(resolveServer("ftp://clinic", file), InputError);
  EXPECT_FALSE(isServerName("ORTHANC@host:4242"));
  EXPECT_TRUE(isServerName("clinic"));
}

TEST(ServerList, AnUnknownNameListsTheSavedNames) {
  const std::filesystem::path dir = test::scratchDir();
  const std::filesystem::path file = write(dir, "servers.json", kServers);
  try {
    resolveServer("clinc", file);
    FAIL() << "an unknown name resolved";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "clinc");
    EXPECT_NE(e.problem().find("saves 'clinic', 'Research PACS'"), std::string::npos)
        << e.problem();
  }
  const std::filesystem::path none = dir / "absent" / "servers.json";
  try {
    resolveServer("clinic", none);
    FAIL() << "a name resolved without a list";
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("no servers are saved (" + none.string() + " does not exist)"),
              std::string::npos)
        << e.problem();
  }
}

// A study config's "pacs" takes a name too; a misspelt one is said with the config's file and
// key, listing the names saved in the default file ($XDG_CONFIG_HOME/mvw/servers.json).
TEST(ServerList, AStudyConfigNamesASavedServer) {
  // XDG_CONFIG_HOME as it was once the test ends, however it ends.
  struct RestoreXdg {
    const char* old = std::getenv("XDG_CONFIG_HOME");
    std::string saved = old ? old : "";
    ~RestoreXdg() {
      if (old)
        setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
      else
        unsetenv("XDG_CONFIG_HOME");
    }
  } restore;
  const std::filesystem::path dir = test::scratchDir();
  setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  std::filesystem::create_directories(dir / "mvw");
  write(dir / "mvw", "servers.json", kServers);
  const auto configOf = [&dir](const std::string& server) {
    return write(
        dir, "study.json",
        R"({"anatomical": {"pacs": ")" + server + R"(", "study": "1.2", "series": "CT"}})");
  };
  EXPECT_EQ(loadStudyConfig(configOf("clinic")).anatomical.pacs, "clinic");
  const std::filesystem::path bad = configOf("clinc");
  try {
    loadStudyConfig(bad);
    ADD_FAILURE() << "an unknown name was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), bad);
    EXPECT_NE(e.problem().find("'anatomical.pacs' is neither"), std::string::npos) << e.problem();
    EXPECT_NE(e.problem().find("'clinic', 'Research PACS'"), std::string::npos) << e.problem();
  }
}

}  // namespace
}  // namespace mvw::config
