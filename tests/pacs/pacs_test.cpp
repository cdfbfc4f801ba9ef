// The PACS client's checks that need no server (the rest: tests/cli/pacs-cli against Orthanc):
// which strings are UIDs (only those name files), which SERVER texts are servers, and how a
// series choice picks one series or refuses.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "Internal.h"
#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::pacs {
namespace {

// QIDO-RS values go out with their wildcards and PN separators as typed: Debian's Orthanc 1.10
// does not decode %2A, %3F or %5E, and answers an escaped search with no match (pacs_cli
// searches it for real). What would change the query is escaped.
TEST(Pacs, QueryValuesKeepWildcardsAndEscapeWhatWouldChangeTheQuery) {
  EXPECT_EQ(detail::queryValue("Doe*"), "Doe*");
  EXPECT_EQ(detail::queryValue("D?e^J*"), "D?e^J*");
  EXPECT_EQ(detail::queryValue("20240101-20241231"), "20240101-20241231");
  EXPECT_EQ(detail::queryValue("1.2.840.10008"), "1.2.840.10008");
  EXPECT_EQ(detail::queryValue("a&b=c+d#e%f"), "a%26b%3Dc%2Bd%23e%25f");
  EXPECT_EQ(detail::queryValue("van der Berg"), "van%20der%20Berg");
  EXPECT_EQ(detail::queryValue("M\xc3\xbcller"), "M%C3%BCller");
  EXPECT_EQ(detail::queryValue(std::string("a\nb\0c", 5)), "a%0Ab%00c");
}

// Issue 50: an instance whose Pixel Data ends early (a well-formed WADO-RS answer cut inside one
// part) was accepted into the verified cache, which then failed every later read. The received-
// instance check parses the whole file: the truncated copy is refused, the whole one accepted.
TEST(Pacs, AnInstanceWhosePixelDataEndsEarlyIsRefused) {
  namespace fs = std::filesystem;
  const fs::path dir = test::scratchDir();
  fs::path whole;
  for (const auto& e : fs::directory_iterator(test::sampleData("cranium/dicom")))
    if (whole.empty() || e.path() < whole) whole = e.path();
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 2000u);
  const fs::path cut = dir / "cut.dcm";
  std::ofstream(cut, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size() - 1000));
  EXPECT_TRUE(detail::readUids(whole).has_value());
  EXPECT_FALSE(detail::readUids(cut).has_value());

  const Server server = parseServer("http://127.0.0.1:1/dicom-web");
  detail::Receiver receiver(server, dir, {}, false);
  try {
    receiver.acceptFile(cut);
    ADD_FAILURE() << "a truncated instance was accepted";
  } catch (const ServiceError& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:1"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(cut));
  EXPECT_EQ(receiver.count(), 0);
}

TEST(Pacs, OnlyUidsNameFiles) {
  EXPECT_TRUE(isUid("1.2.840.10008.5.1.4.1.1.2"));
  EXPECT_TRUE(isUid("2.25.312033976858594262333413331300812186691"));
  EXPECT_TRUE(isUid("1"));
  EXPECT_FALSE(isUid(""));
  EXPECT_FALSE(isUid("../x"));
  EXPECT_FALSE(isUid(".."));
  EXPECT_FALSE(isUid("1..2"));
  EXPECT_FALSE(isUid(".1.2"));
  EXPECT_FALSE(isUid("1.2."));
  EXPECT_FALSE(isUid("1.2/3"));
  EXPECT_FALSE(isUid("1.2\\3"));
  EXPECT_FALSE(isUid("1.2 3"));
  EXPECT_FALSE(isUid(std::string(65, '1')));
  EXPECT_TRUE(isUid(std::string(64, '1')));
}

TEST(Pacs, ServersAreDicomWebOrDimse) {
  Server web = parseServer("http://127.0.0.1:8042/dicom-web/");
  EXPECT_EQ(web.protocol, Protocol::DicomWeb);
  EXPECT_EQ(web.baseUrl, "http://127.0.0.1:8042/dicom-web");
  EXPECT_EQ(parseServer("https://pacs.example.org/wado").protocol, Protocol::DicomWeb);
  Server dimse = parseServer("dicom://ORTHANC@pacs.local:4242");
  EXPECT_EQ(dimse.protocol, Protocol::Dimse);
  EXPECT_EQ(dimse.calledAet, "ORTHANC");
  EXPECT_EQ(dimse.host, "pacs.local");
  EXPECT_EQ(dimse.port, 4242);
  for (const char* bad : {"ftp://x", "dicom://pacs:104", "dicom://A@h:0", "dicom://A@h:70000",
                          "dicom://TOOLONGAETITLE_1234@h:104", "pacs", ""})
    EXPECT_THROW(parseServer(bad), InputError) << bad;
}

TEST(Pacs, CredentialsInAUrlAreRefusedWithoutBeingRepeated) {
  try {
    parseServer("https://alice:hunter2@pacs.example.org/dicom-web");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("hunter2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("MVW_PACS_USER"), std::string::npos) << e.what();
  }
}

TEST(Pacs, ASeriesChoicePicksOneOrRefuses) {
  const Server s = parseServer("http://127.0.0.1:1/dw");
  const std::vector<Match> series = {{{"SeriesInstanceUID", "1.2.3.1"},
                                      {"SeriesNumber", "1"},
                                      {"Modality", "CT"},
                                      {"SeriesDescription", "Head 1.5 mm"}},
                                     {{"SeriesInstanceUID", "1.2.3.2"},
                                      {"SeriesNumber", "2"},
                                      {"Modality", "PT"},
                                      {"SeriesDescription", "PET AC"}},
                                     {{"SeriesInstanceUID", "1.2.3.3"},
                                      {"SeriesNumber", "3"},
                                      {"Modality", "PT"},
                                      {"SeriesDescription", "PET NAC"}}};
  EXPECT_EQ(selectSeries(s, series, "1.2", "1.2.3.3").at("SeriesNumber"), "3");
  EXPECT_EQ(selectSeries(s, series, "1.2", "2").at("SeriesInstanceUID"), "1.2.3.2");
  EXPECT_EQ(selectSeries(s, series, "1.2", "ct").at("SeriesInstanceUID"), "1.2.3.1");
  EXPECT_EQ(selectSeries(s, series, "1.2", "nac").at("SeriesInstanceUID"), "1.2.3.3");
  EXPECT_THROW(selectSeries(s, series, "1.2", "PT"), InputError);   // two PET series
  EXPECT_THROW(selectSeries(s, series, "1.2", "MR"), InputError);   // none
  EXPECT_THROW(selectSeries(s, series, "1.2", "PET"), InputError);  // two descriptions
}

TEST(Pacs, TheCacheFollowsXdgCacheHome) {
  // The environment as it was, afterwards: other tests of this process read HOME.
  struct Restore {
    std::string name;
    std::optional<std::string> value;
    ~Restore() {
      if (value)
        ::setenv(name.c_str(), value->c_str(), 1);
      else
        ::unsetenv(name.c_str());
    }
  };
  auto saved = [](const char* name) {
    const char* v = std::getenv(name);
    return Restore{name, v ? std::optional<std::string>(v) : std::nullopt};
  };
  const Restore home = saved("HOME"), xdg = saved("XDG_CACHE_HOME");
  Options o;
  o.cacheDir = "/tmp/given";
  EXPECT_EQ(cacheRoot(o), std::filesystem::path("/tmp/given"));
  ::setenv("XDG_CACHE_HOME", "/tmp/xdg", 1);
  EXPECT_EQ(cacheRoot(Options{}), std::filesystem::path("/tmp/xdg/mvw/dicom"));
  ::setenv("XDG_CACHE_HOME", "relative", 1);  // not absolute: ignored, as the spec says
  ::setenv("HOME", "/home/u", 1);
  EXPECT_EQ(cacheRoot(Options{}), std::filesystem::path("/home/u/.cache/mvw/dicom"));
}

}  // namespace
}  // namespace mvw::pacs
