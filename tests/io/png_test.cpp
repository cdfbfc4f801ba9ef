// io::writePng and io::readPng, which renders, screenshots, goldens and `mvw validate` go
// through: exact round trips, every PNG colour type read as RGBA8 (files made here by a small
// encoder over zlib, independent of the one under test), and damaged or oversized files refused
// with the file named before any pixel is decoded.
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/core/Image.h"
#include "mvw/io/Png.h"

namespace mvw {
namespace {

namespace fs = std::filesystem;

void put32(std::string& s, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s.push_back(static_cast<char>((v >> shift) & 255));
}

void chunk(std::string& png, const char* type, const std::string& data) {
  put32(png, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  png += body;
  put32(png, static_cast<std::uint32_t>(
                 crc32(0, reinterpret_cast<const Bytef*>(body.data()), body.size())));
}

// A PNG of the given colour type (0 grey, 2 RGB, 4 grey + alpha, 6 RGBA) and bit depth, rows of
// raw samples (filter 0), big-endian for 16 bits. `declaredWidth` > 0 lies about the width.
std::string encode(int width, int height, int colourType, int depth,
                   const std::vector<std::vector<std::uint16_t>>& rows, int declaredWidth = 0) {
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put32(ihdr, static_cast<std::uint32_t>(declaredWidth > 0 ? declaredWidth : width));
  put32(ihdr, static_cast<std::uint32_t>(height));
  ihdr += {static_cast<char>(depth), static_cast<char>(colourType), 0, 0, 0};
  chunk(png, "IHDR", ihdr);
  std::string raw;
  for (const auto& row : rows) {
    raw.push_back(0);
    for (std::uint16_t v : row) {
      if (depth == 16) raw.push_back(static_cast<char>(v >> 8));
      raw.push_back(static_cast<char>(v & 255));
    }
  }
  uLongf size = compressBound(raw.size());
  std::string packed(size, '\0');
  compress(reinterpret_cast<Bytef*>(packed.data()), &size,
           reinterpret_cast<const Bytef*>(raw.data()), raw.size());
  packed.resize(size);
  chunk(png, "IDAT", packed);
  chunk(png, "IEND", "");
  return png;
}

fs::path save(const fs::path& dir, const std::string& name, const std::string& bytes) {
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

TEST(Png, WritesAndReadsBackEveryByteTopRowFirst) {
  const fs::path dir = test::scratchDir();
  Image image(37, 23);  // odd sizes, every alpha value
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(7 * x + y), p[1] = static_cast<std::uint8_t>(11 * y);
      p[2] = static_cast<std::uint8_t>(x * y), p[3] = static_cast<std::uint8_t>(x + 37 * y);
    }
  image.pixel(0, 0)[0] = 255;  // the top-left pixel is the file's first
  io::writePng(image, dir / "out.png");
  const Image back = io::readPng(dir / "out.png");
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  EXPECT_EQ(back.rgba, image.rgba);
  // Nothing but the PNG is left in the folder (atomic write).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(Png, ReadsGreyRgbAlphaAndSixteenBitAsRgba8) {
  const fs::path dir = test::scratchDir();
  // Grey 8: R = G = B, alpha 255.
  Image grey = io::readPng(save(dir, "grey.png", encode(2, 1, 0, 8, {{10, 200}})));
  EXPECT_EQ(grey.rgba, (std::vector<std::uint8_t>{10, 10, 10, 255, 200, 200, 200, 255}));
  // RGB 8 over two rows: row 0 on top.
  Image rgb = io::readPng(save(dir, "rgb.png", encode(1, 2, 2, 8, {{1, 2, 3}, {4, 5, 6}})));
  EXPECT_EQ(rgb.rgba, (std::vector<std::uint8_t>{1, 2, 3, 255, 4, 5, 6, 255}));
  // Grey + alpha 8.
  Image ga = io::readPng(save(dir, "ga.png", encode(1, 1, 4, 8, {{90, 30}})));
  EXPECT_EQ(ga.rgba, (std::vector<std::uint8_t>{90, 90, 90, 30}));
  // RGBA 16: the high byte of each sample.
  Image deep =
      io::readPng(save(dir, "deep.png", encode(1, 1, 6, 16, {{0x1234, 0xABCD, 0x00FF, 0xFF00}})));
  EXPECT_EQ(deep.rgba, (std::vector<std::uint8_t>{0x12, 0xAB, 0x00, 0xFF}));
  // Grey 16.
  Image grey16 = io::readPng(save(dir, "grey16.png", encode(1, 1, 0, 16, {{0x8001}})));
  EXPECT_EQ(grey16.rgba, (std::vector<std::uint8_t>{0x80, 0x80, 0x80, 255}));
}

void expectRefused(const fs::path& file, const std::string& problem) {
  try {
    io::readPng(file);
    ADD_FAILURE() << file << " was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
  }
}

TEST(Png, RefusesMissingForeignDamagedAndOversizedFilesNamingThem) {
  const fs::path dir = test::scratchDir();
  expectRefused(dir / "missing.png", "");
  expectRefused(save(dir, "text.png", "not a picture at all, just words"), "no PNG signature");
  expectRefused(save(dir, "short.png", "\x89PNG"), "shorter than a PNG header");
  // 100000 x 100000 declared over 1 x 1 of data: refused from the header, nothing allocated.
  expectRefused(save(dir, "huge.png", encode(1, 1, 0, 8, {{0}}, 100000)), "over the limit");
  std::vector<std::vector<std::uint16_t>> big(64, std::vector<std::uint16_t>(64 * 3, 77));
  const std::string whole = encode(64, 64, 2, 8, big);
  expectRefused(save(dir, "cut.png", whole.substr(0, whole.size() / 2)), "cannot decode");
}

TEST(Png, RefusesToWriteAnEmptyImageAndLeavesNothing) {
  const fs::path dir = test::scratchDir();
  EXPECT_THROW(io::writePng(Image(), dir / "empty.png"), Error);
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
  EXPECT_THROW(io::writePng(Image(4, 4), dir / "no-such-folder" / "x.png"), InputError);
}

}  // namespace
}  // namespace mvw
