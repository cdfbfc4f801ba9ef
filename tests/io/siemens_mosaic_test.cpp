// Siemens MOSAIC unpacking (io SiemensMosaic) and the CSA header (SV10) parser it reads the
// tile count and slice normal from, on synthetic headers whose answers are known; arbitrary
// bytes never crash the parser. The real-data counterpart is in
// tests/real-data/dicom_geometry_test.cpp.
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "IoTestUtil.h"
#include "SiemensCsa.h"
#include "SiemensMosaic.h"
#include "mvw/core/Volume.h"

namespace {

using mvw::io::detail::CsaHeader;
using mvw::io::detail::unpackMosaic;
using mvw::test::hasNote;

void put32(std::vector<std::uint8_t>& b, std::int32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xff));
}

std::vector<std::uint8_t> csa(
    const std::vector<std::pair<std::string, std::vector<std::string>>>& e) {
  std::vector<std::uint8_t> b = {'S', 'V', '1', '0', 4, 3, 2, 1};
  put32(b, static_cast<std::int32_t>(e.size()));
  put32(b, 77);
  for (const auto& [name, items] : e) {
    std::string field = name;
    field.resize(64, '\0');
    b.insert(b.end(), field.begin(), field.end());
    put32(b, static_cast<std::int32_t>(items.size()));  // vm
    b.insert(b.end(), {'F', 'D', 0, 0});
    put32(b, 4);
    put32(b, static_cast<std::int32_t>(items.size()) + 2);  // two empty padding items
    put32(b, 77);
    for (std::size_t i = 0; i < items.size() + 2; ++i) {
      const std::string text = i < items.size() ? items[i] + std::string(1, '\0') : "";
      for (int x = 0; x < 4; ++x) put32(b, x == 3 ? 77 : static_cast<std::int32_t>(text.size()));
      b.insert(b.end(), text.begin(), text.end());
      while (b.size() % 4) b.push_back(0);
    }
  }
  return b;
}

TEST(SiemensCsa, ParsesTheMosaicElements) {
  const auto bytes = csa({{"EchoLinePosition", {"32"}},
                          {"NumberOfImagesInMosaic", {"12"}},
                          {"SliceNormalVector", {"-0.034", "-0.13355314", "0.99045082"}}});
  std::string why;
  const auto h = CsaHeader::parse(bytes.data(), bytes.size(), &why);
  ASSERT_TRUE(h) << why;
  EXPECT_EQ(h->number("NumberOfImagesInMosaic"), 12.0);
  ASSERT_EQ(h->items("SliceNormalVector").size(), 3u);
  EXPECT_EQ(h->number("SliceNormalVector", 1), -0.13355314);
  EXPECT_FALSE(h->number("SliceNormalVector", 3));
  EXPECT_TRUE(h->items("Absent").empty());
}

TEST(SiemensCsa, ArbitraryBytesNeverCrashOrAllocateFromClaimedSizes) {
  const auto good =
      csa({{"NumberOfImagesInMosaic", {"12"}}, {"SliceNormalVector", {"0", "0", "1"}}});
  std::string why;
  EXPECT_FALSE(CsaHeader::parse(nullptr, 0, &why));
  EXPECT_FALSE(CsaHeader::parse(good.data(), 12, &why));
  for (std::size_t cut = 0; cut < good.size(); ++cut) {
    const std::vector<std::uint8_t> part(good.begin(), good.begin() + cut);
    EXPECT_FALSE(CsaHeader::parse(part.data(), part.size(), &why)) << cut;  // every cut is short
  }
  std::mt19937 rng(14);
  int parsed = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::uint8_t> b = good;
    const int flips = 1 + static_cast<int>(rng() % 6);
    for (int f = 0; f < flips; ++f) {
      const std::size_t at = rng() % b.size();
      // Length-like values: huge, negative, or random bytes.
      if (rng() % 3 == 0 && at + 4 <= b.size()) {
        const std::int32_t v = rng() % 2 ? INT32_MAX : -static_cast<std::int32_t>(rng() % 1000);
        std::memcpy(b.data() + at, &v, 4);
      } else {
        b[at] = static_cast<std::uint8_t>(rng());
      }
    }
    if (const auto h = CsaHeader::parse(b.data(), b.size(), &why)) {
      ++parsed;
      (void)h->number("NumberOfImagesInMosaic");
    } else {
      EXPECT_FALSE(why.empty());
    }
  }
  EXPECT_GT(parsed, 0);
}

TEST(SiemensMosaic, UnpacksTilesAndCorrectsThePosition) {
  // 3 images of 2 x 2 in a 4 x 4 mosaic (2 x 2 tiles, the fourth empty).
  glm::dmat4 w(1.0);
  const glm::dvec3 u(1, 0, 0), v(0, 1, 0);
  w[0] = glm::dvec4(u * 3.0, 0);
  w[1] = glm::dvec4(v * 2.0, 0);
  w[3] = glm::dvec4(-100, 50, 7, 1);
  mvw::Volume m({4, 4, 1}, 1, mvw::ScalarType::Int16, w);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) m.setValue(i, j, 0, 0, 10 * j + i);
  for (const double sign : {1.0, -1.0}) {
    const auto header = csa({{"NumberOfImagesInMosaic", {"3"}},
                             {"SliceNormalVector", {"0", "0", sign > 0 ? "1" : "-1"}}});
    const mvw::Volume out = unpackMosaic(m, header.data(), header.size(), 6.0, 5.0);
    ASSERT_EQ(out.dimensions(), glm::ivec3(2, 2, 3));
    // Shifted by (4 - 2) / 2 = 1 pixel along rows and columns.
    const glm::dvec3 first(-100 + 3, 50 + 2, 7);
    for (int tile = 0; tile < 3; ++tile) {
      const int k = sign > 0 ? tile : 2 - tile;
      const glm::dvec3 at = out.worldFromIndexPoint({0, 0, k});
      EXPECT_NEAR(glm::length(at - (first + glm::dvec3(0, 0, sign * 6.0 * tile))), 0, 1e-9);
      const int x0 = (tile % 2) * 2, y0 = (tile / 2) * 2;
      EXPECT_EQ(out.value(1, 1, k), 10 * (y0 + 1) + x0 + 1);
    }
    EXPECT_GT(glm::determinant(glm::dmat3(out.worldFromIndex())), 0.0);
  }
  // Malformed or absent CSA: kept as one image, with a note.
  std::vector<std::uint8_t> junk(100, 0xff);
  const mvw::Volume kept = unpackMosaic(m, junk.data(), junk.size(), 6.0, 5.0);
  EXPECT_EQ(kept.dimensions(), glm::ivec3(4, 4, 1));
  EXPECT_TRUE(hasNote(kept, "Siemens MOSAIC not unpacked (CSA header: not an SV10"));
  const auto tooMany = csa({{"NumberOfImagesInMosaic", {"1000000"}}});
  EXPECT_EQ(unpackMosaic(m, tooMany.data(), tooMany.size(), 6, 5).dimensions().z, 1);
  const auto odd = csa({{"NumberOfImagesInMosaic", {"9"}}});  // 3 x 3 tiles do not divide 4
  EXPECT_EQ(unpackMosaic(m, odd.data(), odd.size(), 6, 5).dimensions().z, 1);
}

}  // namespace
