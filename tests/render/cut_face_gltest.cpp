// The anatomy on a crop's cut face (issue 36 item 7, MVW_CUT_FACE): a sphere of two tissues
// (100 on the patient's right, x < 0, and 200 on the left) cut through its middle by the crop
// and seen from above. Each cut-face pixel's hit point (its ray and depth) says which tissue it
// shows; under window 300 / level 150 the two must be the greys 85 and 170, as an MPR on the
// plane shows them, in isosurface and composite renders, with the glyphs (every kind) and the
// fusion colour still on the face where the functional attribute is (y > 0).
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

constexpr double kRadius = 28.0;
constexpr double kRight = 100.0, kLeft = 200.0;  // the two tissues (x < 0, x > 0)
constexpr double kWindow = 300.0, kLevel = 150.0;

struct CutScene {
  Volume anatomy =
      makeVolume({65, 65, 65}, test::axisGrid({-32, -32, -32}, {1, 1, 1}), [](glm::dvec3 p) {
        if (glm::length(p) > kRadius) return 0.0f;
        return static_cast<float>(p.x < 0.0 ? kRight : kLeft);
      });
  // The attribute: 0.7 where y > 0 (the posterior half of the face, both tissues), else 0.
  Volume attribute = makeVolume({17, 17, 17}, test::axisGrid({-32, -32, -32}, {4, 4, 4}),
                                [](glm::dvec3 p) { return p.y > 0.0 ? 0.7f : 0.0f; });

  static RenderSettings settings(RenderMode mode) {
    RenderSettings s = test::settingsOf(
        {.mode = mode, .size = {121, 121}, .view = StandardView::Superior, .jitterOff = true});
    s.iso = 50.0;
    s.transfer = transferPreset("mr-default");  // visible from 15 % of the range (30) on
    s.camera.zoom = 1.3;
    s.crop.max = {1.0, 1.0, 0.5};  // the superior half cut away: the face at z = 0
    s.cutFace = CutFace::Anatomy;
    s.window = {kWindow, kLevel};
    s.functionalWindow = {0.0, 1.0};
    return s;
  }
};

int grey(double value) {
  return static_cast<int>(std::lround(255.0 * (value - (kLevel - 0.5 * kWindow)) / kWindow));
}

// Where a pixel's ray meets the surface it shows (world mm), from the frame's depth.
glm::dvec3 hitOf(const RenderedFrame& f, int x, int y) {
  const glm::dvec2 ndc((x + 0.5) / f.image.width * 2 - 1, 1 - (y + 0.5) / f.image.height * 2);
  const WorldRay ray = rayThrough(f.camera, ndc);
  const double t = f.image.depth[static_cast<std::size_t>(y) * f.image.width + x];
  return ray.origin + t * ray.direction;
}

// The face's pixels away from the tissue border, the sphere's rim and the attribute's edge.
enum class Region { None, RightTissue, LeftTissue };
Region regionOf(const RenderedFrame& f, int x, int y, bool withAttribute) {
  const std::size_t i = static_cast<std::size_t>(y) * f.image.width + x;
  if (f.image.depth[i] < 0) return Region::None;
  const glm::dvec3 p = hitOf(f, x, y);
  if (std::abs(p.z) > 0.6 || glm::length(p) > kRadius - 3.0 || std::abs(p.x) < 2.5)
    return Region::None;
  if (withAttribute ? p.y < 6.0 : p.y > -3.0) return Region::None;
  return p.x < 0.0 ? Region::RightTissue : Region::LeftTissue;
}

struct FaceGreys {
  int right = 0, left = 0;        // pixels of each tissue
  int rightOff = 0, leftOff = 0;  // of those, off their expected grey by more than 2
  double rightMean = 0.0, leftMean = 0.0;
};

// Where the attribute is 0 (y < -3): each tissue's pixels against its grey under the window.
FaceGreys faceGreys(const RenderedFrame& f) {
  FaceGreys g;
  for (int y = 0; y < f.image.height; ++y)
    for (int x = 0; x < f.image.width; ++x) {
      const Region r = regionOf(f, x, y, false);
      if (r == Region::None) continue;
      const auto* p = f.image.pixel(x, y);
      const bool right = r == Region::RightTissue;
      const int expected = grey(right ? kRight : kLeft);
      const bool off = std::abs(p[0] - expected) > 2 || p[0] != p[1] || p[1] != p[2];
      (right ? g.right : g.left) += 1;
      (right ? g.rightOff : g.leftOff) += off ? 1 : 0;
      (right ? g.rightMean : g.leftMean) += p[0];
    }
  if (g.right) g.rightMean /= g.right;
  if (g.left) g.leftMean /= g.left;
  return g;
}

// Pixels of the face where the attribute is (y > 6) changed by at least 10 grey levels between
// two renders, per tissue; and changed anywhere the attribute is 0 (y < -3).
struct Changes {
  int right = 0, left = 0, rightCount = 0, leftCount = 0, outside = 0;
};
Changes changes(const RenderedFrame& a, const Image& b) {
  Changes c;
  for (int y = 0; y < a.image.height; ++y)
    for (int x = 0; x < a.image.width; ++x) {
      const auto* p = a.image.pixel(x, y);
      const auto* q = b.pixel(x, y);
      int delta = 0;
      for (int ch = 0; ch < 3; ++ch) delta = std::max(delta, std::abs(p[ch] - q[ch]));
      const Region r = regionOf(a, x, y, true);
      if (r == Region::RightTissue) ++c.rightCount, c.right += delta >= 10 ? 1 : 0;
      if (r == Region::LeftTissue) ++c.leftCount, c.left += delta >= 10 ? 1 : 0;
      if (regionOf(a, x, y, false) != Region::None && delta > 0) ++c.outside;
    }
  return c;
}

void expectTwoGreys(const RenderedFrame& f, const std::string& what) {
  const FaceGreys g = faceGreys(f);
  std::cout << what << ": cut face " << g.right << " px of tissue 100 at mean grey " << g.rightMean
            << " (" << g.rightOff << " off " << grey(kRight) << "), " << g.left
            << " px of tissue 200 at " << g.leftMean << " (" << g.leftOff << " off " << grey(kLeft)
            << ")\n";
  EXPECT_GT(g.right, 400) << what;
  EXPECT_GT(g.left, 400) << what;
  EXPECT_EQ(g.rightOff, 0) << what;
  EXPECT_EQ(g.leftOff, 0) << what;
}

TEST(CutFace, ShowsTheAnatomyUnderTheWindowInIsosurfaceAndComposite) {
  CutScene scene;
  test::Renderer renderer(scene.anatomy);
  for (RenderMode mode : {RenderMode::Isosurface, RenderMode::Composite}) {
    const RenderSettings s = CutScene::settings(mode);
    expectTwoGreys(renderer.render(s), toString(mode));
  }
  // Without the variant the isosurface's face is its one colour: the two tissues the same.
  RenderSettings plain = CutScene::settings(RenderMode::Isosurface);
  plain.cutFace = CutFace::Plain;
  const FaceGreys g = faceGreys(renderer.render(plain));
  EXPECT_GT(g.right, 400);
  EXPECT_NEAR(g.rightMean, g.leftMean, 0.5) << "plain cut face";
  // Uncropped, the variant is not compiled in: the same program and pixels as plain.
  RenderSettings whole = CutScene::settings(RenderMode::Isosurface);
  whole.crop.max = glm::dvec3(1.0);
  const Image anatomy = renderer.render(whole).image;
  whole.cutFace = CutFace::Plain;
  EXPECT_EQ(anatomy.rgba, renderer.render(whole).image.rgba);
}

TEST(CutFace, GlyphsOfEveryKindAndFusionStayOnTheFace) {
  CutScene scene;
  test::Renderer renderer(scene.anatomy);
  renderer.setFunctional(scene.attribute, glm::dmat4(1.0));
  struct Case {
    RenderMode mode;
    std::vector<GlyphKind> kinds;  // empty: bumps (the default shading)
  };
  const std::vector<Case> cases = {{RenderMode::Isosurface, {}},
                                   {RenderMode::Composite, {}},
                                   {RenderMode::Isosurface, {GlyphKind::Rings}},
                                   {RenderMode::Isosurface, {GlyphKind::Ridges}},
                                   {RenderMode::Isosurface, {GlyphKind::Cones}},
                                   {RenderMode::Isosurface, {GlyphKind::Crosses}},
                                   {RenderMode::Composite, {GlyphKind::Crosses}}};
  for (const Case& c : cases) {
    RenderSettings s = CutScene::settings(c.mode);
    s.glyphDiameterMm = 5.0;
    s.glyphs.classKinds = c.kinds;
    const Image plain = renderer.render(s).image;
    s.glyphs.on = true;
    const RenderedFrame glyphs = renderer.render(s);
    const std::string what = toString(c.mode) + " " +
                             (c.kinds.empty() ? std::string("bumps") : glyphKindName(c.kinds[0]));
    // The face keeps its two greys where there is no attribute ...
    expectTwoGreys(glyphs, what);
    // ... and the glyphs change a good share of both tissues' pixels where there is one, about
    // as many as on the plain (beige) face.
    const Changes d = changes(glyphs, plain);
    RenderSettings beige = s;
    beige.cutFace = CutFace::Plain;
    const RenderedFrame beigeGlyphs = renderer.render(beige);
    beige.glyphs.on = false;
    const Changes b = changes(beigeGlyphs, renderer.render(beige).image);
    std::cout << what << ": glyphs change " << d.right << " of " << d.rightCount
              << " px on tissue 100, " << d.left << " of " << d.leftCount << " on tissue 200 ("
              << b.right << ", " << b.left << " on the plain face), " << d.outside
              << " without attribute\n";
    EXPECT_GT(d.rightCount, 300) << what;
    EXPECT_GT(d.leftCount, 300) << what;
    EXPECT_GT(d.right, d.rightCount / 20) << what;
    EXPECT_GT(d.left, d.leftCount / 20) << what;
    EXPECT_GE(d.right, 0.7 * b.right) << what;
    EXPECT_GE(d.left, 0.7 * b.left) << what;
    EXPECT_EQ(d.outside, 0) << what;
  }
  // Fusion: the overlay colour over the face's grey where the attribute is, the grey elsewhere.
  RenderSettings s = CutScene::settings(RenderMode::Isosurface);
  s.overlay.fusion = true;
  s.overlay.opacity = 0.6f;
  s.overlay.threshold = 0.25f;
  const RenderedFrame fused = renderer.render(s);
  expectTwoGreys(fused, "isosurface fusion");
  int coloured = 0, onAttribute = 0;
  for (int y = 0; y < fused.image.height; ++y)
    for (int x = 0; x < fused.image.width; ++x)
      if (regionOf(fused, x, y, true) != Region::None) {
        ++onAttribute;
        const auto* p = fused.image.pixel(x, y);
        if (p[0] - p[2] > 60) ++coloured;
      }
  EXPECT_GT(onAttribute, 600);
  EXPECT_EQ(coloured, onAttribute) << "hot metal at 0.7 over the grey";
}

}  // namespace
}  // namespace mvw::render
