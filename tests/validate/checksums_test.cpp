// Golden-image checksums (validate Checksums), for exact comparison on the GL that made them:
// the pixel digest against Python's, the manifest's round trip and refusals.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/validate/Checksums.h"

namespace mvw::validate {
namespace {

// Expected digests from Python: hashlib.sha256(bytes(pixels) + b"WxHx3").hexdigest().
TEST(Checksums, PixelSha256HashesPixelsAndShape) {
  cv::Mat one(1, 1, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_EQ(pixelSha256(one), "636a2d5f89b59e1e3cf490fd262046164f805a9dc60389ee1eb20b150d2aa7c3");
  const unsigned char six[] = {1, 2, 3, 4, 5, 6};
  const cv::Mat wide(1, 2, CV_8UC3, const_cast<unsigned char*>(six));
  const cv::Mat tall(2, 1, CV_8UC3, const_cast<unsigned char*>(six));
  EXPECT_EQ(pixelSha256(wide), "48f33293624fcae89f15911ec579d37f8811a01bd4fac865b62199e02ca45fe1");
  EXPECT_EQ(pixelSha256(tall), "f0876dc5363e9926e43d070e4fb7b4e1a97a3850545419754cbe963128422306");
  // A region of a larger image (rows not contiguous) hashes as its own pixels.
  cv::Mat big(3, 3, CV_8UC3, cv::Scalar(9, 9, 9));
  big(cv::Rect(1, 1, 1, 1)).setTo(cv::Scalar(1, 2, 3));
  EXPECT_EQ(pixelSha256(big(cv::Rect(1, 1, 1, 1))), pixelSha256(one));
}

TEST(Checksums, ManifestRoundTripAndRefusals) {
  const auto dir = test::scratchDir();
  std::filesystem::create_directories(dir / "golden");
  ChecksumManifest m;
  m.file = dir / "golden" / "checksums.json";
  m.glRenderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  m.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
  m.images[m.keyOf(dir / "golden" / "a.png")] = std::string(64, 'a');
  writeChecksumManifest(m);
  const ChecksumManifest back = loadChecksumManifest(m.file);
  EXPECT_EQ(back.glRenderer, m.glRenderer);
  EXPECT_EQ(back.glVersion, m.glVersion);
  ASSERT_EQ(back.images.count("a.png"), 1u);
  EXPECT_TRUE(back.exactOn(m.glRenderer, m.glVersion));
  EXPECT_FALSE(back.exactOn("AMD Radeon", m.glVersion));
  EXPECT_FALSE(back.exactOn(m.glRenderer, "4.6 Mesa 23"));
  std::ofstream(m.file) << R"({"gl_renderer": "x", "gl_version": "y", "images": {"a.png": "12"}})";
  EXPECT_THROW(loadChecksumManifest(m.file), InputError);
  EXPECT_THROW(loadChecksumManifest(dir / "none.json"), InputError);
}

}  // namespace
}  // namespace mvw::validate
