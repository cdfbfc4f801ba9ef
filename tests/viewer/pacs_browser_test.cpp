// The viewer's PACS browser without a window: servers.json read strictly, the study config the
// choices make (PACS sources, saved and read back), the series choices, a server that cannot be
// reached failing on the background thread with the server named, and the script's pacs-*
// commands.
#include "mvw/viewer/PacsBrowser.h"

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/viewer/ViewerScript.h"

namespace mvw::viewer {
namespace {

using Role = PacsBrowser::Role;

// The file in the test's scratch folder (emptied first: one file a test at a time).
std::filesystem::path write(const std::string& name, const std::string& text) {
  const std::filesystem::path file = test::scratchDir() / name;
  std::ofstream(file) << text;
  return file;
}

// loadServers's problem for `text`, with the file named; "" when it loads.
std::string problemOf(const std::string& text) {
  const std::filesystem::path file = write("servers.json", text);
  try {
    loadServers(file);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    return e.problem();
  }
  return "";
}

const char* kServers =
    R"({"servers": [{"name": "Clinic PACS", "url": "dicom://ORTHANC@127.0.0.1:4242",
                     "calling_aet": "VIEWER"},
                    {"name": "Research", "url": "http://127.0.0.1:1/dicom-web"}]})";

TEST(PacsBrowser, ReadsTheServerList) {
  const auto servers = loadServers(write("servers.json", kServers));
  ASSERT_EQ(servers.size(), 2u);
  EXPECT_EQ(servers[0].name, "Clinic PACS");
  EXPECT_EQ(servers[0].url, "dicom://ORTHANC@127.0.0.1:4242");
  EXPECT_EQ(servers[0].callingAet, "VIEWER");
  EXPECT_EQ(servers[1].callingAet, "MVW");  // the default, as for `mvw pacs`
  EXPECT_TRUE(loadServers(write("empty.json", R"({"servers": []})")).empty());
}

TEST(PacsBrowser, RefusesABadServerList) {
  EXPECT_NE(problemOf("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(problemOf(R"({"server": []})").find("unknown key 'server'"), std::string::npos);
  EXPECT_NE(problemOf(R"({})").find("missing key 'servers'"), std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": "http://h:1/x", "aet": "X"}]})")
                .find("unknown key 'servers[0].aet' (known here: calling_aet, name, url)"),
            std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": "ftp://h/x"}]})").find("servers[0].url"),
            std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": "http://u:pw@h:1/x"}]})")
                .find("credentials in the server URL"),
            std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": "http://h:1/x", "password": "pw"}]})")
                .find("credentials do not belong in the server list"),
            std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": "http://h:1/x"},
                                      {"name": "A", "url": "http://h:2/x"}]})")
                .find("'servers[1]' repeats the name 'A'"),
            std::string::npos);
  EXPECT_NE(
      problemOf(R"({"servers": [{"url": "http://h:1/x"}]})").find("'servers[0]' has no \"name\""),
      std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": "http://h:1/x", "name": "B"}]})")
                .find("appears twice"),
            std::string::npos);
  EXPECT_NE(
      problemOf(R"({"servers": [{"name": "A", "url": "dicom://P@h:104", "calling_aet": ""}]})")
          .find("1 to 16 characters"),
      std::string::npos);
  EXPECT_NE(problemOf(R"({"servers": [{"name": "A", "url": 5}]})")
                .find("'servers[0].url' must be a string"),
            std::string::npos);
}

TEST(PacsBrowser, DefaultServerListFollowsXdgConfigHome) {
  const char* old = std::getenv("XDG_CONFIG_HOME");
  const std::string saved = old ? old : "";
  setenv("XDG_CONFIG_HOME", "/tmp/xdg-test", 1);
  EXPECT_EQ(defaultServersFile(), std::filesystem::path("/tmp/xdg-test/mvw/servers.json"));
  if (old)
    setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
  else
    unsetenv("XDG_CONFIG_HOME");
}

pacs::Match study() {
  return {{"StudyInstanceUID", "1.2.3.4"},
          {"PatientName", "Doe^Jane"},
          {"PatientID", "P-7"},
          {"StudyDate", "20261130"},
          {"ModalitiesInStudy", "CT\\PT"},
          {"StudyDescription", "PET-CT"}};
}

std::vector<pacs::Match> series() {
  return {{{"SeriesInstanceUID", "1.2.3.4.1"},
           {"SeriesNumber", "1"},
           {"Modality", "CT"},
           {"SeriesDescription", "CT low dose"},
           {"NumberOfSeriesRelatedInstances", "108"}},
          {{"SeriesInstanceUID", "1.2.3.4.2"},
           {"SeriesNumber", "2"},
           {"Modality", "PT"},
           {"SeriesDescription", "PET AC"},
           {"NumberOfSeriesRelatedInstances", "44"}},
          {{"SeriesInstanceUID", "1.2.3.4.3"},
           {"SeriesNumber", "3"},
           {"Modality", "SEG"},
           {"SeriesDescription", "lesions"},
           {"NumberOfSeriesRelatedInstances", "1"}}};
}

// The window's tables are the browser's text: the window only lays them out.
TEST(PacsBrowser, TablesRowsAreText) {
  EXPECT_EQ(PacsBrowser::studyRow(study()),
            (std::vector<std::string>{"Doe Jane", "P-7", "2026-11-30", "CT\\PT", "PET-CT", ""}));
  pacs::Match nameless = study();
  nameless.erase("PatientName");
  nameless["StudyDate"] = "2026";  // not YYYYMMDD: as the server gave it
  nameless["NumberOfStudyRelatedSeries"] = "3";
  const std::vector<std::string> row = PacsBrowser::studyRow(nameless);
  EXPECT_EQ(row[0], "(no name)");
  EXPECT_EQ(row[2], "2026");
  EXPECT_EQ(row[5], "3");
  EXPECT_EQ(PacsBrowser::seriesRow(series()[1]),
            (std::vector<std::string>{"2", "PT", "PET AC", "44"}));
  EXPECT_EQ(PacsBrowser::seriesRow({}), (std::vector<std::string>{"", "", "", ""}));
}

TEST(PacsBrowser, ChosenSeriesAreMarked) {
  PacsBrowser b;
  b.takeSeries(series());  // CT as the anatomy, PT as the functional volume
  EXPECT_TRUE(b.isChosen("1.2.3.4.1"));
  EXPECT_TRUE(b.isChosen("1.2.3.4.2"));
  EXPECT_FALSE(b.isChosen("1.2.3.4.3"));
  b.setSeries(Role::Segmentation, "1.2.3.4.3");
  EXPECT_TRUE(b.isChosen("1.2.3.4.3"));
}

// The study date's two fields and the query's DICOM range, both ways.
TEST(PacsBrowser, StudyDateRangeIsTheQuerysRange) {
  PacsBrowser b;
  using Range = std::pair<std::string, std::string>;
  EXPECT_EQ(b.studyDateRange(), Range("", ""));
  b.setStudyDateRange("20260101", "20261231");
  EXPECT_EQ(b.query().studyDate, "20260101-20261231");
  EXPECT_EQ(b.studyDateRange(), Range("20260101", "20261231"));
  b.setStudyDateRange("20260101", "");
  EXPECT_EQ(b.query().studyDate, "20260101-");  // from onwards
  b.setStudyDateRange("", "20261231");
  EXPECT_EQ(b.query().studyDate, "-20261231");  // up to
  EXPECT_EQ(b.studyDateRange(), Range("", "20261231"));
  b.setStudyDateRange("", "");
  EXPECT_EQ(b.query().studyDate, "");
  b.query().studyDate = "20261130";  // a script's study-date= with one date
  EXPECT_EQ(b.studyDateRange(), Range("20261130", ""));
}

TEST(PacsBrowser, ChoicesMakeAStudyConfigNamingPacsSeries) {
  PacsBrowser b;
  const std::filesystem::path file = write("servers.json", kServers);
  b.setServers(loadServers(file), file);
  EXPECT_EQ(b.server(), -1);  // two servers: none chosen for the reader
  EXPECT_FALSE(b.selectServer("Nowhere"));
  ASSERT_TRUE(b.selectServer("Research"));
  EXPECT_EQ(b.options().callingAet, "MVW");
  b.takeStudies({study()});
  EXPECT_EQ(b.status(), "1 study");
  EXPECT_EQ(PacsBrowser::describeStudy(b.studies()[0]),
            "Doe, Jane  ID P-7  2026-11-30  CT\\PT  PET-CT");
  b.chooseStudy(0);  // the series query fails (nothing listens on port 1)
  b.wait();
  b.takeSeries(series());
  // The first choice: CT as the anatomy, PT as the functional volume, no segmentation.
  EXPECT_EQ(b.chosen(Role::Anatomical), "1.2.3.4.1");
  EXPECT_EQ(b.chosen(Role::Functional), "1.2.3.4.2");
  EXPECT_EQ(b.chosen(Role::Segmentation), "");
  EXPECT_EQ(b.functionalKind, config::FunctionalKind::Pet);
  b.chooseSeries(Role::Segmentation, "lesions");  // as `mvw pacs get --series` chooses
  EXPECT_EQ(b.chosen(Role::Segmentation), "1.2.3.4.3");
  EXPECT_EQ(b.describeSeries(b.chosen(Role::Functional)), "#2  PT  PET AC  (44 images)");
  EXPECT_THROW(b.chooseSeries(Role::Functional, "MR"), InputError);  // matches none
  b.registration = config::RegistrationMethod::Rigid;

  const config::StudyConfig s = b.studyConfig();
  EXPECT_EQ(s.name, "Doe, Jane PET-CT (Research)");
  EXPECT_EQ(s.anatomical.pacs, "http://127.0.0.1:1/dicom-web");
  EXPECT_EQ(s.anatomical.study, "1.2.3.4");
  EXPECT_EQ(s.anatomical.series, "1.2.3.4.1");
  EXPECT_TRUE(s.anatomical.path.empty());
  ASSERT_TRUE(s.functional && s.segmentation);
  EXPECT_EQ(s.functional->series, "1.2.3.4.2");
  EXPECT_EQ(s.segmentation->series, "1.2.3.4.3");
  EXPECT_EQ(s.functionalKind, config::FunctionalKind::Pet);
  EXPECT_EQ(s.registration.method, config::RegistrationMethod::Rigid);
  // Written and read back as a study config, the PACS sources stay.
  const std::filesystem::path saved = file.parent_path() / "study.json";
  config::writeStudyConfig(s, saved);
  const config::StudyConfig back = config::loadStudyConfig(saved);
  EXPECT_EQ(back.anatomical.pacs, s.anatomical.pacs);
  EXPECT_EQ(back.functional->study, "1.2.3.4");
  EXPECT_EQ(back.segmentation->series, "1.2.3.4.3");
  // The config is the one a file gives: written again after loading, the same text.
  const std::filesystem::path again = file.parent_path() / "again.json";
  config::writeStudyConfig(back, again);
  auto text = [](const std::filesystem::path& f) {
    std::ifstream in(f);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(again), text(saved));
  // An anonymised study is named by its modalities and date.
  pacs::Match anonymous = study();
  anonymous.erase("PatientName");
  anonymous.erase("PatientID");
  anonymous.erase("StudyDescription");
  b.takeStudies({anonymous});
  b.chooseStudy(0);
  b.wait();
  b.takeSeries(series());
  EXPECT_EQ(b.studyConfig().name, "PACS study CT\\PT 2026-11-30 (Research)");
  // A PET without a CT or MR: read alone, as its own anatomy.
  std::vector<pacs::Match> petAlone = series();
  petAlone.erase(petAlone.begin());
  b.takeSeries(petAlone);
  EXPECT_EQ(b.chosen(Role::Anatomical), "1.2.3.4.2");
  EXPECT_EQ(b.chosen(Role::Functional), "");
  EXPECT_FALSE(b.studyConfig().functional);

  b.setSeries(Role::Anatomical, "");
  EXPECT_THROW(b.studyConfig(), InputError);
  b.open();  // refused before any network: said as the error
  EXPECT_FALSE(b.busy());
  EXPECT_EQ(b.error(), "no anatomical series chosen");
  EXPECT_STREQ(b.failedStep(), "Open");
}

// The options the browser is made with (the command line's --cache and time-outs) are those
// every step uses, with the chosen server's calling AE title and no progress on stderr.
TEST(PacsBrowser, StepsUseTheOptionsItIsMadeWith) {
  pacs::Options given;
  given.cacheDir = "/cache/given";
  given.connectTimeoutS = 2.5;
  given.readTimeoutS = 7.0;
  PacsBrowser b(given);
  b.setServers({{"clinic", "dicom://PACS@127.0.0.1:1", "WS1"}}, "servers.json");
  const pacs::Options o = b.options();
  EXPECT_EQ(o.cacheDir, "/cache/given");
  EXPECT_EQ(o.connectTimeoutS, 2.5);
  EXPECT_EQ(o.readTimeoutS, 7.0);
  EXPECT_EQ(o.callingAet, "WS1");
  EXPECT_FALSE(o.progress);
  EXPECT_EQ(PacsBrowser().options().cacheDir, "");  // made without: the defaults
}

TEST(PacsBrowser, AServerThatCannotBeReachedFailsInTheBackground) {
  PacsBrowser b;
  b.setServers({{"Research", "http://127.0.0.1:1/dicom-web", "MVW"}}, "servers.json");
  EXPECT_EQ(b.server(), 0);  // the only server is chosen
  b.query().modality = "CT";
  b.search();
  EXPECT_TRUE(b.busy());
  EXPECT_NE(b.activity().find("searching Research"), std::string::npos);
  EXPECT_EQ(b.wait(), nullptr);
  EXPECT_FALSE(b.busy());
  EXPECT_NE(b.error().find("http://127.0.0.1:1/dicom-web"), std::string::npos) << b.error();
  EXPECT_TRUE(b.studies().empty());
  EXPECT_STREQ(b.failedStep(), "Search");
}

TEST(PacsBrowser, ScriptCommandsParseAndNameTheirLine) {
  const ViewerScript s = ViewerScript::parse(
      "pacs-server Clinic PACS\n"
      "pacs-search patient-id=P-7 modality=PT study-date=20260101-20261231\n"
      "pacs-study 1\n"
      "pacs-series anatomical CT low dose\n"
      "pacs-series segmentation none\n"
      "pacs-registration rigid\n"
      "pacs-open\n"
      "pacs-report out/pacs.json\n"
      "pacs-open nowait\n"
      "pacs-wait\n"
      "pacs-wait progress\n",
      "test.script");
  const auto& c = s.commands();
  ASSERT_EQ(c.size(), 11u);
  EXPECT_EQ(c[10].frames, -1);
  EXPECT_EQ(c[6].kind, ViewerScript::Command::Kind::PacsOpen);
  EXPECT_NE(c[6].frames, -1);  // waited for
  EXPECT_EQ(c[8].frames, -1);  // nowait
  EXPECT_EQ(c[9].kind, ViewerScript::Command::Kind::PacsWait);
  EXPECT_EQ(c[0].text, "Clinic PACS");
  EXPECT_EQ(c[1].query.patientId, "P-7");
  EXPECT_EQ(c[1].query.modality, "PT");
  EXPECT_EQ(c[1].query.studyDate, "20260101-20261231");
  EXPECT_EQ(c[3].role, Role::Anatomical);
  EXPECT_EQ(c[3].text, "CT low dose");
  EXPECT_EQ(c[4].role, Role::Segmentation);
  EXPECT_EQ(c[5].registration, config::RegistrationMethod::Rigid);
  for (const char* bad :
       {"pacs-search patient=x", "pacs-series liver CT", "pacs-server", "pacs-registration warp",
        "pacs-open now", "pacs-search modality", "pacs-wait 3", "pacs-wait images"}) {
    try {
      ViewerScript::parse(std::string("wait 1\n") + bad + "\n", "test.script");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), std::filesystem::path("test.script"));
      EXPECT_EQ(e.problem().rfind("line 2: ", 0), 0u) << e.problem();
    }
  }
}

TEST(PacsBrowser, ScriptNamesAServerNotInTheList) {
  PacsBrowser b;
  b.setServers({{"Research", "http://127.0.0.1:1/dicom-web", "MVW"}}, "servers.json");
  ViewerScript s = ViewerScript::parse("pacs-server Clinic\n", "test.script");
  try {
    s.step(nullptr, &b);
    ADD_FAILURE() << "an unknown server was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), std::filesystem::path("test.script"));
    EXPECT_NE(e.problem().find("line 1: pacs-server: no server named 'Clinic' in servers.json "
                               "(Research)"),
              std::string::npos)
        << e.problem();
  }
  // Without a study only waits, the PACS and quit run.
  ViewerScript t = ViewerScript::parse("wait 1\nkey 3\n", "test.script");
  EXPECT_TRUE(t.step(nullptr, &b));
  EXPECT_TRUE(t.step(nullptr, &b));
  EXPECT_THROW(t.step(nullptr, &b), InputError);
}

}  // namespace
}  // namespace mvw::viewer
