// What counts as a received instance (issue 50): the size rule of native Pixel Data (8 and 16
// bits, multi-frame, 1-bit SEG with bit counts that do not fill a byte, RGB, YBR_FULL_422) and
// the fragments of encapsulated Pixel Data, on files DCMTK writes here; a retrieve refusing such
// an instance as the server's fault; the verified cache moving a series that no longer verifies
// into its bounded quarantine; and the offline choice of a series (issue 51: by UID without a
// word, by anything else only with a warning naming the UID). The server side is
// tests/cli/pacs-cache, against a real Orthanc.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcpixel.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <gtest/gtest.h>

#include "Internal.h"
#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::pacs {
namespace {

namespace fs = std::filesystem;

const char* kStudy = "1.2.826.0.1.3680043.10.1.1";
const char* kSeries = "1.2.826.0.1.3680043.10.1.2";

struct Image {
  Uint16 rows = 4, columns = 4, samples = 1, bits = 16;
  int frames = 0;  // 0: no Number of Frames
  std::string photometric = "MONOCHROME2";
};

DcmFileFormat dataset(const std::string& sop, const Image& image) {
  DcmFileFormat ff;
  DcmDataset* ds = ff.getDataset();
  ds->putAndInsertString(DCM_SOPClassUID, UID_SecondaryCaptureImageStorage);
  ds->putAndInsertString(DCM_SOPInstanceUID, sop.c_str());
  ds->putAndInsertString(DCM_StudyInstanceUID, kStudy);
  ds->putAndInsertString(DCM_SeriesInstanceUID, kSeries);
  ds->putAndInsertUint16(DCM_Rows, image.rows);
  ds->putAndInsertUint16(DCM_Columns, image.columns);
  ds->putAndInsertUint16(DCM_SamplesPerPixel, image.samples);
  ds->putAndInsertUint16(DCM_BitsAllocated, image.bits);
  ds->putAndInsertString(DCM_PhotometricInterpretation, image.photometric.c_str());
  if (image.frames > 0)
    ds->putAndInsertString(DCM_NumberOfFrames, std::to_string(image.frames).c_str());
  return ff;
}

// A native instance whose Pixel Data holds `bytes` bytes (DCMTK pads an odd count to even).
fs::path writeNative(const fs::path& dir, const std::string& sop, const Image& image,
                     std::size_t bytes) {
  DcmFileFormat ff = dataset(sop, image);
  const std::vector<Uint8> pixels(bytes, 7);
  EXPECT_TRUE(
      ff.getDataset()
          ->putAndInsertUint8Array(DCM_PixelData, pixels.data(), static_cast<unsigned long>(bytes))
          .good());
  const fs::path file = dir / (sop + ".dcm");
  EXPECT_TRUE(ff.saveFile(file.c_str(), EXS_LittleEndianExplicit).good());
  return file;
}

// An encapsulated (JPEG Baseline) instance with `fragments` fragments of 600 bytes and a Basic
// Offset Table holding `offsets` (empty: none).
fs::path writeEncapsulated(const fs::path& dir, const std::string& sop, int frames, int fragments,
                           const std::vector<Uint32>& offsets = {}) {
  Image image;
  image.bits = 8;
  image.frames = frames;
  DcmFileFormat ff = dataset(sop, image);
  auto* seq = new DcmPixelSequence(DCM_PixelSequenceTag);
  auto* table = new DcmPixelItem(DCM_PixelItemTag);
  if (!offsets.empty()) {
    std::vector<Uint8> bytes;
    for (Uint32 o : offsets)
      for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<Uint8>(o >> (8 * b)));
    table->putUint8Array(bytes.data(), static_cast<unsigned long>(bytes.size()));
  }
  seq->insert(table);
  for (int i = 0; i < fragments; ++i) {
    auto* item = new DcmPixelItem(DCM_PixelItemTag);
    const std::vector<Uint8> bytes(600, static_cast<Uint8>(i));
    item->putUint8Array(bytes.data(), static_cast<unsigned long>(bytes.size()));
    seq->insert(item);
  }
  auto* px = new DcmPixelData(DCM_PixelData);
  px->putOriginalRepresentation(EXS_JPEGProcess1, nullptr, seq);
  ff.getDataset()->insert(px);
  const fs::path file = dir / (sop + ".dcm");
  EXPECT_TRUE(ff.saveFile(file.c_str(), EXS_JPEGProcess1).good());
  return file;
}

std::string problemOf(const fs::path& file) {
  const detail::InstanceCheck check = detail::checkInstance(file);
  if (check.ok()) return {};
  EXPECT_FALSE(check.problem.empty()) << file;
  return check.problem;
}

// 16-bit, one frame: 4 x 4 x 2 bytes; a frame's worth short is refused, naming the sizes.
TEST(PacsInstanceCheck, NativeSixteenBitsNeedEveryByte) {
  const fs::path dir = test::scratchDir();
  EXPECT_EQ(problemOf(writeNative(dir, "1.2.3.1", {}, 32)), "");
  const std::string why = problemOf(writeNative(dir, "1.2.3.2", {}, 30));
  EXPECT_NE(why.find("holds 30 bytes"), std::string::npos) << why;
  EXPECT_NE(why.find("need 32"), std::string::npos) << why;
}

// 8-bit, 3 frames of 5 x 3: 45 bytes, padded to 46; two frames' worth is refused.
TEST(PacsInstanceCheck, NativeEightBitsMultiFrameCountEveryFrame) {
  const fs::path dir = test::scratchDir();
  const Image image{.rows = 5, .columns = 3, .samples = 1, .bits = 8, .frames = 3};
  EXPECT_EQ(problemOf(writeNative(dir, "1.2.3.1", image, 45)), "");  // written padded: 46
  EXPECT_NE(problemOf(writeNative(dir, "1.2.3.2", image, 30)), "");
  EXPECT_NE(problemOf(writeNative(dir, "1.2.3.3", image, 44)), "");
}

// A SEG's 1-bit frames are packed across frame boundaries: 3 x 5 x 3 = 45 bits take 6 bytes,
// 7 x 7 = 49 bits take 7 (8 with the pad byte).
TEST(PacsInstanceCheck, OneBitSegFramesArePackedBits) {
  const fs::path dir = test::scratchDir();
  const Image packed{.rows = 3, .columns = 5, .samples = 1, .bits = 1, .frames = 3};
  EXPECT_EQ(problemOf(writeNative(dir, "1.2.3.1", packed, 6)), "");
  EXPECT_NE(problemOf(writeNative(dir, "1.2.3.2", packed, 4)), "");
  const Image odd{.rows = 7, .columns = 7, .samples = 1, .bits = 1, .frames = 1};
  EXPECT_EQ(problemOf(writeNative(dir, "1.2.3.3", odd, 7)), "");
  const std::string why = problemOf(writeNative(dir, "1.2.3.4", odd, 6));
  EXPECT_NE(why.find("need 8"), std::string::npos) << why;
}

// RGB counts three samples a pixel; YBR_FULL_422 two (two pixels share their chroma).
TEST(PacsInstanceCheck, ColourCountsItsSamples) {
  const fs::path dir = test::scratchDir();
  const Image rgb{.rows = 4, .columns = 4, .samples = 3, .bits = 8, .photometric = "RGB"};
  EXPECT_EQ(problemOf(writeNative(dir, "1.2.3.1", rgb, 48)), "");
  EXPECT_NE(problemOf(writeNative(dir, "1.2.3.2", rgb, 32)), "");
  const Image ybr{.rows = 4, .columns = 4, .samples = 3, .bits = 8, .photometric = "YBR_FULL_422"};
  EXPECT_EQ(problemOf(writeNative(dir, "1.2.3.3", ybr, 32)), "");
  EXPECT_NE(problemOf(writeNative(dir, "1.2.3.4", ybr, 30)), "");
}

// Encapsulated: a fragment for every frame, the sequence delimiter, and a Basic Offset Table
// (when there is one) pointing at a fragment for each frame.
TEST(PacsInstanceCheck, EncapsulatedNeedsEveryFragmentAndTheDelimiter) {
  const fs::path dir = test::scratchDir();
  EXPECT_EQ(problemOf(writeEncapsulated(dir, "1.2.3.1", 2, 2)), "");
  EXPECT_EQ(problemOf(writeEncapsulated(dir, "1.2.3.2", 2, 2, {0, 608})), "");
  EXPECT_EQ(problemOf(writeEncapsulated(dir, "1.2.3.3", 1, 3)), "");  // a frame in 3 fragments
  const std::string missing = problemOf(writeEncapsulated(dir, "1.2.3.4", 2, 1));
  EXPECT_NE(missing.find("1 fragment for 2 frames"), std::string::npos) << missing;
  EXPECT_NE(problemOf(writeEncapsulated(dir, "1.2.3.5", 2, 2, {0, 100})), "");
  EXPECT_NE(problemOf(writeEncapsulated(dir, "1.2.3.6", 2, 2, {0})), "");
  // The sequence delimiter (its last 8 bytes) cut off: the dataset does not parse.
  const fs::path whole = writeEncapsulated(dir, "1.2.3.7", 2, 2);
  fs::resize_file(whole, fs::file_size(whole) - 8);
  EXPECT_NE(problemOf(whole).find("does not parse"), std::string::npos) << problemOf(whole);
  // A fragment cut inside.
  const fs::path cut = writeEncapsulated(dir, "1.2.3.8", 2, 2);
  fs::resize_file(cut, fs::file_size(cut) - 300);
  EXPECT_NE(problemOf(cut), "");
}

// No pixels (an SR, a registration): nothing to count.
TEST(PacsInstanceCheck, AnInstanceWithoutPixelsCounts) {
  const fs::path dir = test::scratchDir();
  DcmFileFormat ff;
  ff.getDataset()->putAndInsertString(DCM_SOPClassUID, UID_SpatialRegistrationStorage);
  ff.getDataset()->putAndInsertString(DCM_SOPInstanceUID, "1.2.3.9");
  ASSERT_TRUE(ff.saveFile((dir / "reg.dcm").c_str(), EXS_LittleEndianExplicit).good());
  EXPECT_EQ(problemOf(dir / "reg.dcm"), "");
}

// A retrieve refuses an instance short of pixels as the server's fault, naming both.
TEST(PacsInstanceCheck, ARetrieveRefusesAShortInstanceNamingServerAndInstance) {
  const fs::path dir = test::scratchDir();
  const fs::path file = writeNative(dir, "1.2.3.77", {}, 16);
  const Server server = parseServer("http://127.0.0.1:1/dicom-web");
  detail::Receiver receiver(server, dir, {}, false);
  try {
    receiver.acceptFile(file);
    ADD_FAILURE() << "an instance short of pixels was accepted";
  } catch (const ServiceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("127.0.0.1:1"), std::string::npos) << what;
    EXPECT_NE(what.find("1.2.3.77"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(file));
  EXPECT_EQ(receiver.count(), 0);
}

// A complete series in the cache: `count` whole instances and its .complete.
fs::path cacheSeries(const Server& server, const Options& options, int count) {
  const fs::path dir = detail::studyFolder(server, kStudy, options) / kSeries;
  fs::create_directories(dir);
  std::ofstream complete(dir / ".complete");
  for (int i = 1; i <= count; ++i) {
    const std::string sop = std::string(kSeries) + "." + std::to_string(i);
    writeNative(dir, sop, {}, 32);
    complete << sop << "\n";
  }
  return dir;
}

std::string hex(const std::string& text) {
  std::string out;
  char b[3];
  for (unsigned char c : text) {
    std::snprintf(b, sizeof b, "%02x", c);
    out += b;
  }
  return out;
}

// Nothing listens on port 1: every request fails at once, as with a server that is down.
Options offline(const fs::path& dir) {
  Options options;
  options.cacheDir = dir / "cache";
  options.connectTimeoutS = 2.0;
  options.progress = false;
  return options;
}

// Offline, a series named by UID reads from a complete cache without a word; one named by
// modality reads only as the series it chose last time, with a warning naming that UID.
TEST(PacsInstanceCheck, OfflineAUidReadsSilentlyAndADescriptionWithAWarning) {
  const fs::path dir = test::scratchDir();
  const Options options = offline(dir);
  const Server server = parseServer("http://127.0.0.1:1/dicom-web");
  const fs::path series = cacheSeries(server, options, 2);
  testing::internal::CaptureStderr();
  EXPECT_EQ(cachedSeries(server, kStudy, kSeries, options), series);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  // Never chosen by "CT" before: the server must answer.
  EXPECT_THROW(cachedSeries(server, kStudy, "CT", options), ServiceError);
  std::ofstream(detail::studyFolder(server, kStudy, options) / ("selection-" + hex("CT")))
      << kSeries << "\n";
  testing::internal::CaptureStderr();
  EXPECT_EQ(cachedSeries(server, kStudy, "CT", options), series);
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("warning"), std::string::npos) << said;
  EXPECT_NE(said.find(std::string("as series ") + kSeries), std::string::npos) << said;
  EXPECT_NE(said.find("127.0.0.1:1"), std::string::npos) << said;
}

// A cached series whose file no longer verifies (pixels cut short, as a poisoned cache had)
// moves into the quarantine, said on stderr, and is retrieved again: here the server is down,
// so the read fails as a server fault instead of failing on the cached file forever.
TEST(PacsInstanceCheck, ACachedSeriesThatNoLongerVerifiesIsQuarantined) {
  const fs::path dir = test::scratchDir();
  const Options options = offline(dir);
  const Server server = parseServer("http://127.0.0.1:1/dicom-web");
  const fs::path series = cacheSeries(server, options, 3);
  writeNative(series, std::string(kSeries) + ".2", {}, 10);
  testing::internal::CaptureStderr();
  EXPECT_THROW(cachedSeries(server, kStudy, kSeries, options), ServiceError);
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(fs::exists(series));
  const QuarantineSize held = quarantineSize(options);
  EXPECT_EQ(held.series, 1);
  EXPECT_GT(held.bytes, 0u);
  EXPECT_NE(said.find(quarantineRoot(options).string()), std::string::npos) << said;
  EXPECT_NE(said.find(std::string(kSeries) + ".2.dcm"), std::string::npos) << said;
  const QuarantineSize cleared = clearQuarantine(options);
  EXPECT_EQ(cleared.series, 1);
  EXPECT_EQ(quarantineSize(options).series, 0);
}

// The quarantine keeps its newest series and drops the oldest beyond its limit; only series
// folders of the cache move into it.
TEST(PacsInstanceCheck, TheQuarantineIsBoundedAndTakesOnlyCachedSeries) {
  const fs::path dir = test::scratchDir();
  Options options = offline(dir);
  const Server server = parseServer("http://127.0.0.1:1/dicom-web");
  std::vector<fs::path> moved;
  for (int i = 0; i < 3; ++i) {
    const fs::path series = cacheSeries(server, options, 2);
    moved.push_back(quarantineSeries(series, "test " + std::to_string(i), options, 1000));
    EXPECT_FALSE(fs::exists(series));
    EXPECT_TRUE(fs::exists(moved.back() / "why.txt"));
  }
  // Each holds two files of about 400 bytes: a 1000-byte limit keeps the newest alone.
  EXPECT_FALSE(fs::exists(moved[0]));
  EXPECT_FALSE(fs::exists(moved[1]));
  EXPECT_TRUE(fs::exists(moved[2]));
  EXPECT_EQ(quarantineSize(options).series, 1);
  fs::create_directories(dir / "elsewhere" / "1.2.3");
  EXPECT_THROW(quarantineSeries(dir / "elsewhere" / "1.2.3", "no", options), InputError);
  EXPECT_THROW(quarantineSeries(moved[2], "no", options), InputError);
}

}  // namespace
}  // namespace mvw::pacs
