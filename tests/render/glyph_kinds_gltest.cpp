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
#include "mvw/io/Png.h"
#include "mvw/render/Framing.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::render {
namespace {

constexpr double kSphereMm = 70.0, kBandMm = 18.0, kLabelVoxelMm = 4.0;
constexpr int kBands = 6, kImage = 600;
constexpr int kFeatures = 22;  // see describe
using Features = std::array<double, kFeatures>;

struct Tile {
  int truth = 0;   // the kind meant where the glyph lies (its band's)
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

// One glyph's patch: a connected blob of changed pixels (D = glyph render - plain render, grey
// levels; |D| >= 4, joined across one-pixel seams such as a ridge's crest, where the normal is
// the surface's own). Described in its own frame, so that the view and the light's strength
// matter little: how much of its disc is changed, how elongated it is, how the change is
// spread over three rings from its centre, how it varies around the centre (2 and 4 fold:
// bars and crosses), its signed balance and the side the light brightens (bumps vs dimples).
Features describe(const std::vector<double>& d, int w, const std::vector<int>& pixels,
                  double glyphRadiusPx) {
  double cx = 0.0, cy = 0.0;
  for (int p : pixels) cx += p % w, cy += p / w;
  cx /= pixels.size(), cy /= pixels.size();
  double sxx = 0.0, syy = 0.0, sxy = 0.0, sumAbs = 0.0, sumD = 0.0, light = 0.0;
  std::array<double, 3> ringAbs{}, ringChanged{}, ringCount{};
  std::array<double, 16> sector{};
  const double rho = std::sqrt(pixels.size() / M_PI);
  for (int p : pixels) {
    const double x = p % w - cx, y = p / w - cy, v = d[std::size_t(p)];
    sxx += x * x, syy += y * y, sxy += x * y;
    sumAbs += std::abs(v), sumD += v;
    light += v * (-x - y) / std::sqrt(2.0) / rho;  // toward the upper left (image y down)
    const double r = std::sqrt(x * x + y * y) / rho;
    const int ring = r < 0.4 ? 0 : r < 0.75 ? 1 : 2;
    ringAbs[std::size_t(ring)] += std::abs(v), ringCount[std::size_t(ring)] += 1.0;
    const bool changed = std::abs(v) >= 4.0;
    ringChanged[std::size_t(ring)] += changed;
    if (changed && r > 0.25) {
      const int s = int((std::atan2(y, x) + M_PI) / (2.0 * M_PI) * 16.0) % 16;
      sector[std::size_t(s)] += 1.0;
    }
  }
  const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
  const double root = std::sqrt(std::max(tr * tr / 4.0 - det, 0.0));
  const double elongation = std::sqrt(std::max(tr / 2.0 - root, 0.0) / (tr / 2.0 + root + 1e-9));
  auto harmonic = [&](int m) {
    double c = 0.0, s = 0.0, total = 0.0;
    for (int i = 0; i < 16; ++i) {
      const double a = (i + 0.5) * 2.0 * M_PI / 16.0;
      c += sector[std::size_t(i)] * std::cos(m * a), s += sector[std::size_t(i)] * std::sin(m * a);
      total += sector[std::size_t(i)];
    }
    return total > 0.0 ? std::sqrt(c * c + s * s) / total : 0.0;
  };
  const double meanAbs = sumAbs / pixels.size() + 1e-9;
  // The signed and the absolute change in five rings of the glyph's disc, against the mean.
  std::array<double, 5> profile{}, profileAbs{}, profileN{};
  for (int p : pixels) {
    const double x = p % w - cx, y = p / w - cy, v = d[std::size_t(p)];
    const int ring = std::min(4, int(std::sqrt(x * x + y * y) / rho * 4.0));
    profile[std::size_t(ring)] += v, profileAbs[std::size_t(ring)] += std::abs(v);
    profileN[std::size_t(ring)] += 1.0;
  }
  for (int i = 0; i < 5; ++i) {
    profile[std::size_t(i)] /= std::max(profileN[std::size_t(i)], 1.0) * meanAbs;
    profileAbs[std::size_t(i)] /= std::max(profileN[std::size_t(i)], 1.0) * meanAbs;
  }
  Features f{};
  f = {elongation,
       ringAbs[0] / std::max(ringCount[0], 1.0) / meanAbs,
       ringAbs[1] / std::max(ringCount[1], 1.0) / meanAbs,
       ringAbs[2] / std::max(ringCount[2], 1.0) / meanAbs,
       ringChanged[0] / std::max(ringCount[0], 1.0),
       ringChanged[1] / std::max(ringCount[1], 1.0),
       ringChanged[2] / std::max(ringCount[2], 1.0),
       harmonic(2),
       harmonic(4),
       sumD / sumAbs,
       light / (sumAbs + 1e-9),
       rho / glyphRadiusPx,
       profile[0],
       profile[1],
       profile[2],
       profile[3],
       profile[4],
       profileAbs[0],
       profileAbs[1],
       profileAbs[2],
       profileAbs[3],
       profileAbs[4]};
  return f;
}

struct Result {
  std::vector<std::vector<int>> confusion;  // [truth kind][assigned kind]
  int right = 0, total = 0;
};

// k nearest neighbours (k = 7, features scaled by their spread) among the tiles of the other
// renders, assigning each tile the kind of the band most of them came from.
Result classify(const std::vector<Tile>& tiles, int kinds) {
  Features mean{}, spread{};
  for (const Tile& t : tiles)
    for (int i = 0; i < kFeatures; ++i) mean[i] += t.f[i] / tiles.size();
  for (const Tile& t : tiles)
    for (int i = 0; i < kFeatures; ++i)
      spread[i] += (t.f[i] - mean[i]) * (t.f[i] - mean[i]) / tiles.size();
  for (double& s : spread) s = std::sqrt(s) + 1e-9;
  // Three cues a reader looks at first weigh more: the side the light brightens (bumps against
  // dimples), and the two- and four-fold pattern around the centre (bars, crosses).
  spread[10] /= 3.0, spread[7] /= 2.0, spread[8] /= 2.0;
  std::vector<double> count(std::size_t(kinds), 1e-9);
  for (const Tile& t : tiles) count[std::size_t(t.truth)] += 1.0;
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
      near.emplace_back(d2, o.truth);
    }
    const std::size_t k = std::min<std::size_t>(7, near.size());
    std::partial_sort(near.begin(), near.begin() + long(k), near.end());
    // Each neighbour's vote weighs 1 / (its kind's share of the tiles): a kind with many
    // glyphs in view (bars split, a band seen face-on) does not outvote the others.
    std::vector<double> votes(std::size_t(kinds), 0.0);
    for (std::size_t i = 0; i < k; ++i)
      votes[std::size_t(near[i].second)] += 1.0 / count[std::size_t(near[i].second)];
    const int assigned = int(std::max_element(votes.begin(), votes.end()) - votes.begin());
    const int truth = t.truth;
    ++r.confusion[std::size_t(truth)][std::size_t(assigned)];
    r.right += assigned == truth, ++r.total;
  }
  return r;
}

void print(const Result& r, const std::vector<std::string>& names, const char* title) {
  std::printf("\n%s: %d of %d glyph patches (%.1f %%) assigned to their band's kind\n%-9s", title,
              r.right, r.total, 100.0 * r.right / std::max(r.total, 1), "truth \\ as");
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
                          const std::vector<GlyphKind>& meant, glm::dvec2 light,
                          const std::string& tag, int renderBase, double* spacingOut) {
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
    double spacing =
        study::defaultGlyphSpacingMm(kLabelVoxelMm, perPixel, s.glyphMinSize, /*kinds=*/true);
    if (const char* px = std::getenv("MVW_KIND_PX"))  // measuring the glyph size: radius, px
      spacing = std::atof(px) * perPixel / (0.5 * kBlueNoiseDiameterFraction);
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
        if (glm::dot(glm::normalize(hit), -ray.direction) < 0.5) continue;
        band[std::size_t(y) * kImage + x] = bandAt(hit.z, 0.5 * spacing);
      }
    // The blobs: changed pixels grown by one pixel, 8-connected.
    const double glyphRadiusPx = 0.5 * s.glyphDiameterMm / perPixel;
    std::vector<char> grown(d.size(), 0);
    for (int y = 1; y < kImage - 1; ++y)
      for (int x = 1; x < kImage - 1; ++x)
        if (std::abs(d[std::size_t(y) * kImage + x]) >= 4.0)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) grown[std::size_t(y + dy) * kImage + x + dx] = 1;
    std::vector<char> seen(d.size(), 0);
    for (int start = 0; start < kImage * kImage; ++start) {
      if (!grown[std::size_t(start)] || seen[std::size_t(start)]) continue;
      std::vector<int> blob = {start}, stack = {start};
      seen[std::size_t(start)] = 1;
      bool edge = false;
      while (!stack.empty()) {
        const int p = stack.back();
        stack.pop_back();
        const int x = p % kImage, y = p / kImage;
        edge |= x == 0 || y == 0 || x == kImage - 1 || y == kImage - 1;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= kImage || yy >= kImage) continue;
            const int q = yy * kImage + xx;
            if (grown[std::size_t(q)] && !seen[std::size_t(q)])
              seen[std::size_t(q)] = 1, blob.push_back(q), stack.push_back(q);
          }
      }
      // One glyph: not a speck, not several run together.
      const double area = double(blob.size()), disc = M_PI * glyphRadiusPx * glyphRadiusPx;
      if (edge || area < 0.25 * disc || area > 1.6 * disc) continue;
      double cx = 0.0, cy = 0.0;
      for (int p : blob) cx += p % kImage, cy += p / kImage;
      const int middle = int(std::lround(cy / area)) * kImage + int(std::lround(cx / area));
      const int b = band[std::size_t(middle)];
      if (b < 0) continue;
      tiles.push_back({int(meant[std::size_t(b)]), renderBase + int(v),
                       describe(d, kImage, blob, glyphRadiusPx)});
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
  // Each set three times, its kinds turned by two bands, so that every kind is seen both near the
  // sphere's equator and towards a pole.
  auto run = [&](const std::vector<GlyphKind>& drawn, const std::vector<GlyphKind>& meant,
                 glm::dvec2 light, const std::string& tag, const char* title) {
    double spacing = 0.0;
    std::vector<Tile> tiles;
    for (int shift : {0, 2, 4}) {
      std::vector<GlyphKind> d, m;
      for (int b = 0; b < kBands; ++b)
        d.push_back(drawn[std::size_t((b + shift) % kBands)]),
            m.push_back(meant[std::size_t((b + shift) % kBands)]);
      const std::vector<Tile> t =
          tilesOf(renderer, d, m, light, tag + std::to_string(shift), 4 * shift, &spacing);
      tiles.insert(tiles.end(), t.begin(), t.end());
    }
    const Result r = classify(tiles, kGlyphKindCount);
    if (std::getenv("MVW_KIND_FEATURES"))  // the features' means per kind, for a closer look
      for (int k = 0; k < kGlyphKindCount; ++k) {
        Features mean{};
        int n = 0;
        for (const Tile& t : tiles)
          if (t.truth == k) {
            ++n;
            for (int i = 0; i < kFeatures; ++i) mean[std::size_t(i)] += t.f[std::size_t(i)];
          }
        std::printf("\n%-8s", names[std::size_t(k)].c_str());
        for (double x : mean) std::printf(" %6.2f", n ? x / n : 0.0);
      }
    std::printf("\n[%s] glyph spacing %.2f mm (the product's default), %zu glyph patches",
                tag.c_str(), spacing, tiles.size());
    print(r, names, title);
    return r;
  };
  const std::vector<GlyphKind> all = {GlyphKind::Bumps,  GlyphKind::Dimples, GlyphKind::Rings,
                                      GlyphKind::Ridges, GlyphKind::Cones,   GlyphKind::Crosses};
  const Result lit = run(all, all, {-0.8, 0.8}, "lit", "six kinds, light from the upper left");
  // Under a headlight bumps and dimples shade alike (mirror images about the surface normal
  // make the same angle with the line of sight): the headlight set is the five other kinds.
  const std::vector<GlyphKind> five = {GlyphKind::Bumps,  GlyphKind::Bumps, GlyphKind::Rings,
                                       GlyphKind::Ridges, GlyphKind::Cones, GlyphKind::Crosses};
  const Result head =
      run(five, five, {0.0, 0.0}, "headlight", "five kinds, headlight (the default light)");
  // Two kinds made the same: the crosses' band drawn as rings, still meant as crosses.
  std::vector<GlyphKind> same = all;
  same[5] = GlyphKind::Rings;
  const Result merged = run(same, all, {-0.8, 0.8}, "same", "crosses drawn as rings (must fail)");
  EXPECT_GE(lit.right, 0.9 * lit.total);
  EXPECT_LT(merged.right, 0.9 * merged.total);
  EXPECT_GE(head.right, 0.9 * head.total);
}

}  // namespace
}  // namespace mvw::render
