// Volumetric normal glyphs (Seipel 2007): no attribute is plain shading, glyphs stay where the
// attribute is and grow with it, convex and concave flip the lit side, and they stay visible
// in composite DVR as the opacity is lowered.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/Framing.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

// A sphere (radius 25 mm) seen as an isosurface, and a functional attribute that is zero
// on the patient's right (x < 0) and `level` on the left (x > 0).
struct GlyphScene {
  Volume anatomy =
      makeVolume({61, 61, 61}, test::axisGrid({-30, -30, -30}, {1, 1, 1}),
                 [](glm::dvec3 p) { return static_cast<float>(25.0 - glm::length(p)); });
  // An isosurface of the sphere, seen from the front (screen right = patient left = +x),
  // glyphs on, the attribute mapped 0..1, many glyphs (4 mm) over the 50 mm sphere.
  static RenderSettings settings() {
    RenderSettings s = test::settingsOf({.mode = RenderMode::Isosurface,
                                         .size = {241, 241},
                                         .view = StandardView::Anterior,
                                         .jitterOff = true});
    s.iso = 0.0;
    s.glyphs.on = true;
    s.glyphDiameterMm = 4.0;
    s.functionalWindow = {0.0, 1.0};
    return s;
  }
  static Volume attribute(float level) {
    return makeVolume({16, 16, 16}, test::axisGrid({-30, -30, -30}, {4, 4, 4}),
                      [level](glm::dvec3 p) { return p.x > 2.0 ? level : 0.0f; });
  }
};

int changedPixels(const Image& a, const Image& b, int* leftHalfChanges = nullptr) {
  int n = 0, rightOfScreen = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const auto* p = a.pixel(x, y);
      const auto* q = b.pixel(x, y);
      if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) {
        ++n;
        if (x < a.width / 2 - 1) ++rightOfScreen;
      }
    }
  if (leftHalfChanges) *leftHalfChanges = rightOfScreen;
  return n;
}

TEST(Glyphs, NoAttributeGivesPlainShadingAndGlyphsStayWhereTheAttributeIs) {
  GlyphScene scene;
  test::Renderer renderer(scene.anatomy);
  RenderSettings s = GlyphScene::settings();
  s.glyphs.on = false;
  const RenderedFrame plain = renderer.render(s);
  // beta = 0 everywhere: bit for bit the plain image.
  renderer.setFunctional(GlyphScene::attribute(0.0f), glm::dmat4(1.0));
  s.glyphs.on = true;
  EXPECT_EQ(renderer.render(s).image.rgba, plain.image.rgba);
  // beta > 0 on the left half only: changes appear, and only on the screen's right half.
  renderer.setFunctional(GlyphScene::attribute(0.8f), glm::dmat4(1.0));
  int wrongSide = 0;
  const int changed = changedPixels(renderer.render(s).image, plain.image, &wrongSide);
  // 16 glyphs of 32 voxels in a 128^3 map fill 13 % of space; on the sphere's right half
  // (about 5000 pixels here) half of the cut glyphs face the viewer.
  EXPECT_GT(changed, 150);
  EXPECT_EQ(wrongSide, 0);
}

TEST(Glyphs, ApparentBumpSizeGrowsWithTheAttribute) {
  GlyphScene scene;
  test::Renderer renderer(scene.anatomy);
  RenderSettings s = GlyphScene::settings();
  const RenderedFrame plain = [&] {
    RenderSettings p = s;
    p.glyphs.on = false;
    return renderer.render(p);
  }();
  int previous = 0;
  for (float level : {0.25f, 0.5f, 1.0f}) {
    renderer.setFunctional(GlyphScene::attribute(level), glm::dmat4(1.0));
    const int changed = changedPixels(renderer.render(s).image, plain.image);
    std::cout << "beta " << level << ": " << changed << " pixels changed\n";
    EXPECT_GT(changed, previous) << "beta " << level;
    previous = changed;
  }
  // Dimples change the same places as bumps, with other shading.
  renderer.setFunctional(GlyphScene::attribute(1.0f), glm::dmat4(1.0));
  const RenderedFrame bumps = renderer.render(s);
  s.glyphs.convexity = GlyphConvexity::Dimples;
  const RenderedFrame dimples = renderer.render(s);
  EXPECT_GT(changedPixels(bumps.image, dimples.image), previous / 2);
}

TEST(Glyphs, ConvexAndConcaveFlipTheLitSide) {
  // One glyph (map period 80 mm, glyph 20 mm); a slab whose anterior face lies 3 mm in front
  // of the glyph's centre, lit from the screen's left. A bump is brighter on its left half, a
  // dimple on its right half.
  GlyphMapSettings one{64, 1, 16.0, 5};
  const GlyphMap map = makeGlyphMap(one);
  const double period = 80.0, R = 10.0;
  const glm::dvec3 c = map.centres[0] / 64.0 * period;  // world mm (one period from 0)
  const double face = c.y - 3.0;
  // Both volumes centred on the glyph, so its centre is the middle of the image.
  const glm::dvec3 origin = c - 40.0;
  const Volume slab = makeVolume({81, 81, 81}, test::axisGrid(origin, {1, 1, 1}),
                                 [face](glm::dvec3 p) { return static_cast<float>(p.y - face); });
  const Volume attribute =
      makeVolume({9, 9, 9}, test::axisGrid(origin, {10, 10, 10}), [](glm::dvec3) { return 1.0f; });
  test::Renderer renderer(slab);
  renderer.setFunctional(attribute, glm::dmat4(1.0));
  RenderSettings s = test::settingsOf({
      .mode = RenderMode::Isosurface,
      .size = {161, 161},
      .view = StandardView::Anterior,  // screen right = +x, up = +z
      .jitterOff = true,
  });
  s.iso = 0.0;
  s.camera.zoom = framingSphere(slab).radius / 40.5;  // 0.5 mm per pixel over the 80 mm slab
  s.glyphs.on = true;
  s.glyphMap = one;
  s.glyphDiameterMm = 2 * R;
  s.functionalWindow = {0.0, 1.0};
  s.lightOffset = {-1.0, 0.0};
  const double px = 80.0, py = 80.0;  // the glyph centre on screen
  auto sides = [&](const Image& img) {
    double left = 0, right = 0;
    int nl = 0, nr = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const double dx = x - px, dy = y - py;
        if (dx * dx + dy * dy > (0.8 * R * 2) * (0.8 * R * 2) || std::abs(dx) < 2) continue;
        (dx < 0 ? left : right) += img.pixel(x, y)[0];
        ++(dx < 0 ? nl : nr);
      }
    return std::pair<double, double>{left / std::max(nl, 1), right / std::max(nr, 1)};
  };
  s.glyphs.convexity = GlyphConvexity::Bumps;
  const auto [bumpLeft, bumpRight] = sides(renderer.render(s).image);
  s.glyphs.convexity = GlyphConvexity::Dimples;
  const auto [dimpleLeft, dimpleRight] = sides(renderer.render(s).image);
  std::cout << "bump left/right " << bumpLeft << "/" << bumpRight << ", dimple " << dimpleLeft
            << "/" << dimpleRight << "\n";
  EXPECT_GT(bumpLeft, bumpRight + 10);
  EXPECT_GT(dimpleRight, dimpleLeft + 10);
}

// Seipel's claim for DVR: the glyphs stay visible while the opacity transfer function is
// lowered. The distance-field sphere in composite DVR, its opacity per step scaled from
// surface-like (0.9) to faint (0.05); the attribute on the right half. At every opacity the
// glyphs change a similar share of the sphere's pixels, visibly, and never the left half.
TEST(Glyphs, StayVisibleInCompositeDvrAsTheOpacityIsLowered) {
  GlyphScene scene;
  test::Renderer renderer(scene.anatomy);
  renderer.setFunctional(GlyphScene::attribute(0.8f), glm::dmat4(1.0));
  RenderSettings s = GlyphScene::settings();
  s.mode = RenderMode::Composite;
  s.lightOffset = {-0.8, 0.8};
  std::vector<double> shares, contrasts;
  // Measured on llvmpipe (Mesa 22.3.6) at opacity 0.9, 0.3, 0.1, 0.05: the share of the
  // sphere's right half changed by > 4, and the mean change over the brightness. Asserted
  // within 25 % of these (other GL implementations filter the glyph map a little differently);
  // the "7.9-13.0 %" in docs/user-guide/glyphs.md is this test's output.
  const double measuredShare[] = {0.0791, 0.1305, 0.1303, 0.0796};
  const double measuredContrast[] = {0.0220, 0.0220, 0.0174, 0.0122};
  int step = 0;
  for (double opacity : {0.9, 0.3, 0.1, 0.05}) {
    const glm::vec3 c(0.9f, 0.85f, 0.8f);
    s.transfer = {"step", false, {{-0.5, glm::vec4(c, 0.0f)}, {0.5, glm::vec4(c, float(opacity))}}};
    s.glyphs.on = false;
    const Image plain = renderer.render(s).image;
    s.glyphs.on = true;
    const Image glyphs = renderer.render(s).image;
    int sphere = 0, changed = 0, wrongSide = 0;
    double delta = 0.0, level = 0.0;
    for (int y = 0; y < plain.height; ++y)
      for (int x = 0; x < plain.width; ++x) {
        const auto* p = plain.pixel(x, y);
        const auto* q = glyphs.pixel(x, y);
        const int d =
            std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])});
        if (x < plain.width / 2 - 1) {
          wrongSide += d != 0;
          continue;
        }
        if (x <= plain.width / 2 + 1 || p[0] + p[1] + p[2] == 0) continue;
        ++sphere;
        changed += d > 4;
        delta += d;
        level += p[0];
      }
    const double share = double(changed) / sphere, contrast = delta / level;
    std::cout << "opacity " << opacity << ": " << 100.0 * share
              << " % of the sphere's right half changed by > 4, "
              << "mean change " << 100.0 * contrast << " % of its brightness\n";
    EXPECT_EQ(wrongSide, 0) << "opacity " << opacity;
    shares.push_back(share);
    contrasts.push_back(contrast);
    EXPECT_NEAR(share, measuredShare[step], 0.25 * measuredShare[step]) << "opacity " << opacity;
    EXPECT_NEAR(contrast, measuredContrast[step], 0.25 * measuredContrast[step])
        << "opacity " << opacity;
    ++step;
  }
  EXPECT_GT(shares.back(), 0.5 * shares.front());
}

}  // namespace
}  // namespace mvw::render
