// Glyphs on the visible surface (issue 52, RenderSettings::glyphs.onSurface): the legend's icons
// still match the image. A plane facing the camera in five bands, one glyph kind each, on the
// isosurface with the glyphs on the surface (as the icons' own plane); the legend's icons for
// the same view (VolumeRenderer::renderGlyphIcons). Each icon must hold one whole glyph in its
// middle, and described as the reader describes a glyph patch (tests/render/GlyphReader.h) it
// must lie nearest the image's patches of its own kind (the mean of each kind's patches, the
// features scaled by their spread over the image's patches). Fails where the icons show the
// lattice's slivers or another shape than the image draws.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "GlyphReader.h"
#include "RenderTestUtil.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/io/Png.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::render {
namespace {

namespace reader = test::reader;

constexpr double kOnSurfaceBandMm = 20.0;
constexpr int kOnSurfaceBands = 5, kOnSurfaceImage = 600, kIconPixels = 64;
const std::array<GlyphKind, kOnSurfaceBands> kOnSurfaceKinds = {
    GlyphKind::Bumps, GlyphKind::Rings, GlyphKind::Ridges, GlyphKind::Cones, GlyphKind::Crosses};

// The band of height z (-1: outside, or within `margin` of a band's edge).
int onSurfaceBand(double z, double margin) {
  const double u = (z + kOnSurfaceBands * kOnSurfaceBandMm / 2) / kOnSurfaceBandMm;
  const int b = int(std::floor(u));
  if (b < 0 || b >= kOnSurfaceBands) return -1;
  const double frac = (u - b) * kOnSurfaceBandMm;
  return frac < margin || frac > kOnSurfaceBandMm - margin ? -1 : b;
}

TEST(GlyphsOnTheSurface, TheLegendIconsMatchTheImage) {
  // A plane facing an anterior camera (tissue posterior of y = 0), as the icon's own plane is.
  const Volume slab = test::makeVolume(
      {161, 161, 161}, makeWorldFromIndex({-80, -80, -80}, {1, 1, 1}, glm::dmat3(1.0)),
      [](glm::dvec3 p) { return float(p.y); });
  const Volume labels = test::makeVolume(
      {41, 41, 41}, makeWorldFromIndex({-80, -80, -80}, glm::dvec3(4.0), glm::dmat3(1.0)),
      [](glm::dvec3 p) { return float(onSurfaceBand(p.z, 0.0) + 1); });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, slab);
  renderer.setFunctional(labels, glm::dmat4(1.0));

  RenderSettings s;
  s.mode = RenderMode::Isosurface;
  s.camera.view = StandardView::Anterior;
  s.camera.zoom = 1.6;
  s.size = {kOnSurfaceImage, kOnSurfaceImage};
  s.iso = 0.0;
  s.jitter = false;
  s.overlay.mpr = false;
  const double perPixel = 2.0 * renderer.radius() / s.camera.zoom / s.size.x;
  const double spacing = study::defaultGlyphSpacingMm(4.0, perPixel, s.glyphs.minSize, true);
  s.glyphMap = blueNoiseGlyphMap(spacing, kBlueNoiseDiameterFraction * spacing, 1);
  s.glyphDiameterMm = kBlueNoiseDiameterFraction * spacing;
  for (int b = 0; b < kOnSurfaceBands; ++b)
    s.glyphLabels.push_back({b + 1, kOnSurfaceKinds[b], ""});
  s.glyphs.onSurface = true;
  RenderSettings plainS = s;
  plainS.glyphs.on = false;
  s.glyphs.on = true;
  const RenderedFrame plain = renderer.render(plainS), glyphs = renderer.render(s);
  const std::filesystem::path out =
      std::filesystem::path(MVW_TEST_OUTPUT_DIR) / "glyphs-on-the-surface";
  std::filesystem::create_directories(out);
  io::writePng(glyphs.image, out / "plane.png");

  // The image's glyph patches and the kind meant where each lies.
  const std::vector<double> d = reader::glyphChange(glyphs.image, plain.image);
  const int n = kOnSurfaceImage;
  std::vector<int> band(std::size_t(n) * n, -1);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float t = plain.image.depth[std::size_t(y) * n + x];
      if (t < 0.0f) continue;
      const WorldRay ray =
          rayThrough(plain.camera, {(x + 0.5) / n * 2.0 - 1.0, 1.0 - (y + 0.5) / n * 2.0});
      const glm::dvec3 hit = ray.origin + double(t) * ray.direction;
      band[std::size_t(y) * n + x] = onSurfaceBand(hit.z, 0.5 * s.glyphDiameterMm);
    }
  const double radiusPx = 0.5 * s.glyphDiameterMm / perPixel;
  std::vector<reader::Tile> tiles;
  for (const reader::Blob& blob : reader::changedBlobs(d, n, n)) {
    const int b = band[std::size_t(blob.middle)];
    if (b < 0 || !reader::isGlyphPatch(blob, radiusPx)) continue;
    tiles.push_back({b, 0, reader::describe(d, n, blob.pixels, radiusPx)});
  }
  std::array<int, kOnSurfaceBands> perKind{};
  for (const reader::Tile& t : tiles) ++perKind[std::size_t(t.truth)];
  for (int b = 0; b < kOnSurfaceBands; ++b)
    ASSERT_GE(perKind[std::size_t(b)], 5) << glyphKindName(kOnSurfaceKinds[b]) << " in the image";
  reader::Features spread{};
  std::array<reader::Features, kOnSurfaceBands> mean{};
  for (const reader::Tile& t : tiles)
    for (int i = 0; i < reader::kFeatures; ++i)
      mean[std::size_t(t.truth)][i] += t.f[i] / perKind[std::size_t(t.truth)];
  for (int i = 0; i < reader::kFeatures; ++i) {
    double m = 0.0, v = 0.0;
    for (const reader::Tile& t : tiles) m += t.f[i] / tiles.size();
    for (const reader::Tile& t : tiles) v += (t.f[i] - m) * (t.f[i] - m) / tiles.size();
    spread[i] = std::sqrt(v) + 1e-9;
  }

  // The legend's icons, each against the same icon with no attribute (a plain plane).
  GlyphLegend legend;
  for (int b = 0; b < kOnSurfaceBands; ++b)
    legend.entries.push_back({"", 1.0, kOnSurfaceKinds[b], Image{}, double(b + 1)});
  legend.entries.push_back({"", 1.0, GlyphKind::Bumps, Image{}, 0.0});
  renderer.renderGlyphIcons(s, legend, kIconPixels);
  const Image& blank = legend.entries.back().icon;
  ASSERT_EQ(blank.width, kIconPixels);
  for (int b = 0; b < kOnSurfaceBands; ++b) {
    const std::string kind = glyphKindName(kOnSurfaceKinds[b]);
    const Image& icon = legend.entries[std::size_t(b)].icon;
    io::writePng(icon, out / ("icon-" + kind + ".png"));
    const std::vector<double> di = reader::glyphChange(icon, blank);
    const std::vector<reader::Blob> blobs = reader::changedBlobs(di, kIconPixels, kIconPixels);
    // One glyph, whole (off the icon's border) and in the middle.
    ASSERT_EQ(blobs.size(), 1u) << kind << ": the icon holds " << blobs.size() << " glyphs";
    EXPECT_FALSE(blobs[0].edge) << kind << ": the icon's glyph is cut by its border";
    double cx = 0.0, cy = 0.0;
    for (int p : blobs[0].pixels) cx += p % kIconPixels, cy += p / kIconPixels;
    cx /= blobs[0].pixels.size(), cy /= blobs[0].pixels.size();
    EXPECT_LT(std::hypot(cx - 0.5 * kIconPixels, cy - 0.5 * kIconPixels), 2.5) << kind;
    // Its radius as a disc of the blob's area: the icon's glyph radius in pixels.
    const double iconRadius = std::sqrt(blobs[0].pixels.size() / M_PI);
    const reader::Features f = reader::describe(di, kIconPixels, blobs[0].pixels, iconRadius);
    int nearest = -1;
    double best = 1e30;
    for (int k = 0; k < kOnSurfaceBands; ++k) {
      double d2 = 0.0;
      for (int i = 0; i < reader::kFeatures; ++i) {
        // The size relative to the glyph radius is the icon's own here: not a cue.
        if (i == 11) continue;
        const double dd = (f[i] - mean[std::size_t(k)][i]) / spread[i];
        d2 += dd * dd;
      }
      if (d2 < best) best = d2, nearest = k;
    }
    EXPECT_EQ(nearest, b) << kind << "'s icon reads as the image's "
                          << glyphKindName(kOnSurfaceKinds[std::size_t(nearest)]);
  }
}

}  // namespace
}  // namespace mvw::render
