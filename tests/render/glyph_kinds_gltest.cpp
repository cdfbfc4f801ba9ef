// Can a reader tell the glyph kinds apart? (issue 40, item 4.) A sphere of 70 mm radius (a
// curved surface seen from every direction at once) under a label map of six bands along S,
// each band a label of its own kind (bumps, dimples, rings, ridges, cones, crosses) at the
// product's default glyph spacing for a 4 mm label voxel and the view's scale. From the render
// alone (the glyph render against the plain one, the truth being the band the pixel's ray
// meets first on the sphere), the image is cut into tiles inside one band; each tile is
// described by a few shading statistics and classified by its nearest neighbours among the
// tiles of the OTHER renders (leave one render out: the classifier never sees the render it
// judges). Renders: two view directions (anterior; oblique from the upper left) x isosurface
// and low-opacity composite DVR, with the product's default light (a headlight) and with a
// light from the upper left. The confusion matrix is printed. Required: >= 90 % of tiles
// assigned to their band's kind, for the kinds a view's light can tell apart; and the same
// measurement over a set in which two bands carry the same kind stays below 90 % (the test
// fails when two kinds are made the same). Deterministic: no jitter, seeded glyph map.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/io/PngWriter.h"
#include "mvw/render/Framing.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::render {
namespace {

constexpr double kSphereMm = 70.0, kBandMm = 22.0, kLabelVoxelMm = 4.0;
constexpr int kBands = 6, kImage = 400, kTile = 20;
constexpr int kFeatures = 12;
using Features = std::array<double, kFeatures>;

struct Tile {
  int truth = 0;   // the band (label - 1)
  int render = 0;  // which render it came from
  Features f{};
};

// The band of a point on the sphere (-1: outside every band, or too near a band's edge for a
// glyph of its own band to cover it whole).
int bandAt(double z, double margin) {
  const double u = (z + kBands * kBandMm / 2) / kBandMm;
  const int b = int(std::floor(u));
  if (b < 0 || b >= kBands) return -1;
  const double frac = (u - b) * kBandMm;
  return frac < margin || frac > kBandMm - margin ? -1 : b;
}

double grey(const Image& im, int x, int y) {
  const auto* p = im.pixel(x, y);
  return (p[0] + p[1] + p[2]) / 3.0;
}

// Shading statistics of one tile of D = glyph render - plain render (grey levels): how much
// of it is darkened or brightened and how strongly, how thin the dark marks are, how often a
// row or column crosses a mark, and how the gradient of D is oriented (one direction:
// ridges; two at right angles: crosses; none: round glyphs).
Features describe(const std::vector<double>& d, int w, int x0, int y0) {
  constexpr double t = 6.0;
  Features f{};
  int dark = 0, bright = 0, thick = 0, crossings = 0;
  double sumD = 0.0, sumAbs = 0.0, jxx = 0.0, jyy = 0.0, jxy = 0.0;
  std::array<double, 4> orient{};  // gradient energy at 0, 45, 90, 135 degrees
  auto at = [&](int x, int y) { return d[std::size_t(y) * w + x]; };
  for (int y = y0; y < y0 + kTile; ++y)
    for (int x = x0; x < x0 + kTile; ++x) {
      const double v = at(x, y);
      dark += v <= -t, bright += v >= t;
      sumD += v, sumAbs += std::abs(v);
      if (v <= -t && at(x - 1, y) <= -t && at(x + 1, y) <= -t && at(x, y - 1) <= -t &&
          at(x, y + 1) <= -t)
        ++thick;
      crossings += (v <= -t) != (at(x + 1, y) <= -t);
      crossings += (v <= -t) != (at(x, y + 1) <= -t);
      const double gx = at(x + 1, y) - at(x - 1, y), gy = at(x, y + 1) - at(x, y - 1);
      jxx += gx * gx, jyy += gy * gy, jxy += gx * gy;
      const double e = gx * gx + gy * gy;
      if (e > 0.0) {
        const double a = std::atan2(gy, gx);  // -pi .. pi; orientation mod pi in 4 bins
        const int bin = int(std::lround(std::fmod(a + 2.0 * M_PI, M_PI) / (M_PI / 4))) % 4;
        orient[std::size_t(bin)] += e;
      }
    }
  const double n = kTile * kTile;
  const double energy = orient[0] + orient[1] + orient[2] + orient[3] + 1e-9;
  const double coherence =
      std::sqrt((jxx - jyy) * (jxx - jyy) + 4.0 * jxy * jxy) / (jxx + jyy + 1e-9);
  std::array<double, 4> o = orient;
  std::sort(o.begin(), o.end());
  // The strongest pair of orientations at right angles against the other pair.
  const double pair = std::max(orient[0] + orient[2], orient[1] + orient[3]) / energy;
  f = {dark / n,
       bright / n,
       sumD / n / 40.0,
       sumAbs / n / 40.0,
       dark > 0 ? double(thick) / dark : 0.0,
       crossings / (2.0 * n),
       coherence,
       o[3] / energy,
       pair,
       std::sqrt(jxx + jyy) / n / 10.0,
       dark + bright > 0 ? double(bright) / (dark + bright) : 0.0,
       sumAbs > 0 ? sumD / sumAbs : 0.0};
  return f;
}

struct Result {
  std::vector<std::vector<int>> confusion;  // [truth kind][assigned kind]
  int right = 0, total = 0;
};

// k nearest neighbours (k = 7, features scaled by their spread) among the tiles of the other
// renders, assigning each tile the kind of the band most of them came from.
Result classify(const std::vector<Tile>& tiles, const std::vector<int>& kindOfBand, int kinds) {
  Features mean{}, spread{};
  for (const Tile& t : tiles)
    for (int i = 0; i < kFeatures; ++i) mean[i] += t.f[i] / tiles.size();
  for (const Tile& t : tiles)
    for (int i = 0; i < kFeatures; ++i)
      spread[i] += (t.f[i] - mean[i]) * (t.f[i] - mean[i]) / tiles.size();
  for (double& s : spread) s = std::sqrt(s) + 1e-9;
  Result r;
  r.confusion.assign(std::size_t(kinds), std::vector<int>(std::size_t(kinds), 0));
  for (const Tile& t : tiles) {
    std::vector<std::pair<double, int>> near;
    for (const Tile& o : tiles) {
      if (o.render == t.render) continue;
      double d2 = 0.0;
      for (int i = 0; i < kFeatures; ++i) {
        const double d = (t.f[i] - o.f[i]) / spread[i];
        d2 += d * d;
      }
      near.emplace_back(d2, kindOfBand[std::size_t(o.truth)]);
    }
    const std::size_t k = std::min<std::size_t>(7, near.size());
    std::partial_sort(near.begin(), near.begin() + long(k), near.end());
    std::vector<double> votes(std::size_t(kinds), 0.0);
    for (std::size_t i = 0; i < k; ++i) votes[std::size_t(near[i].second)] += 1.0 / (1.0 + i);
    const int assigned = int(std::max_element(votes.begin(), votes.end()) - votes.begin());
    const int truth = kindOfBand[std::size_t(t.truth)];
    ++r.confusion[std::size_t(truth)][std::size_t(assigned)];
    r.right += assigned == truth, ++r.total;
  }
  return r;
}

void print(const Result& r, const std::vector<std::string>& names, const char* title) {
  std::printf("\n%s: %d of %d tiles (%.1f %%) assigned to their band's kind\n%-9s", title, r.right,
              r.total, 100.0 * r.right / std::max(r.total, 1), "truth \\ as");
  for (const std::string& n : names) std::printf(" %8s", n.c_str());
  std::printf("\n");
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::printf("%-9s", names[i].c_str());
    for (int c : r.confusion[i]) std::printf(" %8d", c);
    std::printf("\n");
  }
}

struct Scene {
  Volume sphere = test::makeVolume({161, 161, 161},
                                   makeWorldFromIndex({-80, -80, -80}, {1, 1, 1}, glm::dmat3(1.0)),
                                   [](glm::dvec3 p) { return float(kSphereMm - glm::length(p)); });
  Volume labels = test::makeVolume(
      {41, 41, 41}, makeWorldFromIndex({-80, -80, -80}, glm::dvec3(kLabelVoxelMm), glm::dmat3(1.0)),
      [](glm::dvec3 p) { return float(bandAt(p.z, 0.0) + 1); });
};

// Renders every view of `kinds` (kind per band) and returns the tiles; writes the renders.
std::vector<Tile> tilesOf(VolumeRenderer& renderer, const std::vector<GlyphKind>& kindOfBand,
                          glm::dvec2 light, const std::string& tag, double* spacingOut) {
  struct View {
    std::string name;
    RenderMode mode;
    CameraSettings camera;
  };
  CameraSettings anterior, oblique;
  anterior.view = oblique.view = StandardView::Anterior;
  oblique.azimuthDeg = -40.0, oblique.elevationDeg = 25.0;
  anterior.zoom = oblique.zoom = 1.6;
  const std::vector<View> views = {{"anterior-isosurface", RenderMode::Isosurface, anterior},
                                   {"oblique-isosurface", RenderMode::Isosurface, oblique},
                                   {"anterior-composite", RenderMode::Composite, anterior},
                                   {"oblique-composite", RenderMode::Composite, oblique}};
  const std::filesystem::path out = std::filesystem::path(MVW_TEST_OUTPUT_DIR) / "glyph-kinds";
  std::filesystem::create_directories(out);
  std::vector<Tile> tiles;
  for (std::size_t v = 0; v < views.size(); ++v) {
    RenderSettings s;
    s.mode = views[v].mode;
    s.camera = views[v].camera;
    s.size = {kImage, kImage};
    s.isoValue = 0.0;
    s.jitter = false;
    s.lightOffset = light;
    s.overlay = false;
    // Low-opacity DVR: 0.1 per step inside the sphere.
    const glm::vec4 c(0.9f, 0.85f, 0.8f, 0.0f);
    s.transfer = {"step", false, {{-0.5, c}, {0.5, glm::vec4(glm::vec3(c), 0.1f)}}};
    // The product's default glyph size for a 4 mm label voxel at this scale.
    const double perPixel = 2.0 * renderer.radius() / s.camera.zoom / s.size.x;
    double spacing = study::defaultGlyphSpacingMm(kLabelVoxelMm, perPixel, s.glyphMinSize);
    if (const char* px = std::getenv("MVW_KIND_PX"))
      spacing = std::max(spacing, std::atof(px) * perPixel / (0.5 * kBlueNoiseDiameterFraction));
    *spacingOut = spacing;
    s.glyphMap = blueNoiseGlyphMap(spacing, kBlueNoiseDiameterFraction * spacing, 1);
    s.glyphDiameterMm = kBlueNoiseDiameterFraction * spacing;
    for (int b = 0; b < kBands; ++b)
      s.glyphLabels.push_back({b + 1, kindOfBand[std::size_t(b)], ""});
    RenderSettings plainS = s;
    plainS.glyphs = false;
    s.glyphs = true;
    const RenderedFrame plain = renderer.render(plainS);
    const RenderedFrame glyphs = renderer.render(s);
    io::writePng(glyphs.image, out / (tag + "-" + views[v].name + ".png"));
    // The middle of the image three times enlarged (a reader's close look).
    Image zoom(3 * kImage / 2, 3 * kImage / 2);
    for (int y = 0; y < zoom.height; ++y)
      for (int x = 0; x < zoom.width; ++x)
        std::copy_n(glyphs.image.pixel(kImage / 4 + x / 3, kImage / 4 + y / 3), 4,
                    zoom.pixel(x, y));
    io::writePng(zoom, out / (tag + "-" + views[v].name + "-zoom.png"));
    std::vector<double> d(std::size_t(kImage) * kImage);
    std::vector<int> band(std::size_t(kImage) * kImage, -1);
    for (int y = 0; y < kImage; ++y)
      for (int x = 0; x < kImage; ++x) {
        d[std::size_t(y) * kImage + x] = grey(glyphs.image, x, y) - grey(plain.image, x, y);
        const WorldRay ray = rayThrough(
            glyphs.camera, {(x + 0.5) / kImage * 2.0 - 1.0, 1.0 - (y + 0.5) / kImage * 2.0});
        // The first meeting with the sphere: |o + t d| = R.
        const double bq = glm::dot(ray.origin, ray.direction);
        const double cq = glm::dot(ray.origin, ray.origin) - kSphereMm * kSphereMm;
        const double disc = bq * bq - cq;
        if (disc <= 0.0) continue;
        const glm::dvec3 hit = ray.origin + (-bq - std::sqrt(disc)) * ray.direction;
        // Away from grazing rims (where a tile spans a great depth), and inside a band by
        // more than a glyph's radius.
        if (glm::dot(glm::normalize(hit), -ray.direction) < 0.3) continue;
        band[std::size_t(y) * kImage + x] = bandAt(hit.z, 0.5 * spacing);
      }
    for (int y0 = 1; y0 + kTile < kImage - 1; y0 += kTile)
      for (int x0 = 1; x0 + kTile < kImage - 1; x0 += kTile) {
        const int b = band[std::size_t(y0) * kImage + x0];
        bool one = b >= 0;
        for (int y = y0 - 1; y <= y0 + kTile && one; ++y)
          for (int x = x0 - 1; x <= x0 + kTile && one; ++x)
            one = band[std::size_t(y) * kImage + x] == b;
        if (!one) continue;
        tiles.push_back({b, int(v), describe(d, kImage, x0, y0)});
      }
  }
  return tiles;
}

TEST(GlyphKinds, AReaderTellsTheKindsApartFromTheRenderAlone) {
  Scene scene;
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, scene.sphere);
  renderer.setFunctional(scene.labels, glm::dmat4(1.0));
  std::vector<std::string> names;
  for (int k = 0; k < kGlyphKindCount; ++k) names.push_back(glyphKindName(GlyphKind(k)));
  // drawn: the kind each band is rendered with; meant: the kind the reader should read there.
  auto run = [&](const std::vector<GlyphKind>& drawn, const std::vector<GlyphKind>& meant,
                 glm::dvec2 light, const std::string& tag, const char* title) {
    double spacing = 0.0;
    const std::vector<Tile> tiles = tilesOf(renderer, drawn, light, tag, &spacing);
    std::vector<int> kindOfBand;
    for (GlyphKind k : meant) kindOfBand.push_back(int(k));
    const Result r = classify(tiles, kindOfBand, kGlyphKindCount);
    std::printf("\n[%s] glyph spacing %.2f mm (the product's default), %zu tiles", tag.c_str(),
                spacing, tiles.size());
    print(r, names, title);
    return r;
  };
  const std::vector<GlyphKind> all = {GlyphKind::Bumps,  GlyphKind::Dimples, GlyphKind::Rings,
                                      GlyphKind::Ridges, GlyphKind::Cones,   GlyphKind::Crosses};
  const Result lit = run(all, all, {-0.8, 0.8}, "lit", "six kinds, light from the upper left");
  const Result head = run(all, all, {0.0, 0.0}, "headlight", "six kinds, headlight (the default)");
  // Two kinds made the same: the crosses' band drawn as rings, still meant as crosses.
  std::vector<GlyphKind> same = all;
  same[5] = GlyphKind::Rings;
  const Result merged = run(same, all, {-0.8, 0.8}, "same", "crosses drawn as rings (must fail)");
  EXPECT_GE(lit.right, 0.9 * lit.total);
  EXPECT_LT(merged.right, 0.9 * merged.total);
  (void)head;
}

}  // namespace
}  // namespace mvw::render
