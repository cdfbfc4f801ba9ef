// The reader of glyph kinds (tests/render/GlyphReader.h) on images drawn here: blobs, the
// patch filter, a few features and the classifier's rule that a tile is judged by other groups.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "GlyphReader.h"

namespace mvw::test::reader {
namespace {

constexpr int kW = 60, kH = 40;

// A disc of `radius` px at (cx, cy), changed by `value`.
void disc(std::vector<double>& d, double cx, double cy, double radius, double value) {
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (std::hypot(x - cx, y - cy) <= radius) d[std::size_t(y) * kW + x] = value;
}

TEST(GlyphReader, CutsTheChangeIntoBlobsAndKeepsWholeGlyphs) {
  std::vector<double> d(std::size_t(kW) * kH, 0.0);
  disc(d, 15, 20, 5, 20.0);     // a glyph
  disc(d, 40, 20, 0.5, -30.0);  // a speck
  disc(d, 58, 5, 4, 10.0);      // cut by the border
  const std::vector<Blob> blobs = changedBlobs(d, kW, kH);
  ASSERT_EQ(blobs.size(), 3u);
  EXPECT_FALSE(blobs[2].edge);  // found in row order: the border's first
  EXPECT_TRUE(blobs[0].edge);
  EXPECT_EQ(blobs[1].middle, 20 * kW + 15);
  // A blob is the change grown by a pixel: a 5 px disc is a 6 px glyph's patch.
  EXPECT_TRUE(isGlyphPatch(blobs[1], 6.0));
  EXPECT_FALSE(isGlyphPatch(blobs[2], 6.0));  // a speck of a 6 px glyph
  EXPECT_FALSE(isGlyphPatch(blobs[0], 4.0));  // at the border
  EXPECT_FALSE(isGlyphPatch(blobs[1], 2.5));  // several 2.5 px glyphs run together
}

TEST(GlyphReader, DescribesABarByItsTwoFoldPatternAndElongation) {
  std::vector<double> round(std::size_t(kW) * kH, 0.0), bar = round;
  disc(round, 30, 20, 8, 20.0);
  for (int y = 17; y <= 23; ++y)
    for (int x = 20; x <= 40; ++x) bar[std::size_t(y) * kW + x] = 20.0;
  const Blob r = changedBlobs(round, kW, kH).at(0), b = changedBlobs(bar, kW, kH).at(0);
  const Features fr = describe(round, kW, r.pixels, 8.0), fb = describe(bar, kW, b.pixels, 8.0);
  EXPECT_GT(fr[0], 0.9);  // elongation: minor / major axis
  EXPECT_LT(fb[0], 0.6);
  EXPECT_GT(fb[7], fr[7] + 0.3);  // the two-fold harmonic
  EXPECT_NEAR(fr[9], 1.0, 1e-9);  // all brighter
}

Tile tile(int truth, int group, double x) {
  Tile t{truth, group, {}};
  t.f[0] = x;  // the only feature that differs
  return t;
}

TEST(GlyphReader, ClassifiesByTheOtherGroupsOnly) {
  std::vector<Tile> tiles;
  for (int g = 0; g < 2; ++g)
    for (int i = 0; i < 4; ++i)
      tiles.push_back(tile(0, g, 0.1 * i)), tiles.push_back(tile(1, g, 10.0 + 0.1 * i));
  Result r = classify(tiles, 2);
  EXPECT_EQ(r.right, r.total);
  EXPECT_EQ(r.total, 16);
  EXPECT_EQ(r.confusion[0][0], 8);
  // The two groups' kinds swapped: every tile's nearest tiles are its own group's, which never
  // vote, so every tile is read as the other kind.
  tiles.clear();
  for (int g = 0; g < 2; ++g)
    for (int i = 0; i < 4; ++i)
      tiles.push_back(tile(g, g, 0.1 * i)), tiles.push_back(tile(1 - g, g, 10.0 + 0.1 * i));
  r = classify(tiles, 2);
  EXPECT_EQ(r.total, 16);
  EXPECT_EQ(r.right, 0);
}

}  // namespace
}  // namespace mvw::test::reader
