// The ray caster against numbers that can be checked by hand: a real CT's maximum projection,
// a sphere's isosurface distance, Beer-Lambert through a slab, and where L, P and S land.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <gtest/gtest.h>

#include "../unit/TestUtil.h"
#include "mvw/core/VesselPhantom.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

Volume makeVolume(glm::ivec3 dims, const glm::dmat4& worldFromIndex, const std::function<float(glm::dvec3)>& f) {
  Volume v(dims, 1, ScalarType::Float32, worldFromIndex);
  float* p = v.dataAs<float>();
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) *p++ = f(v.worldFromIndexPoint({i, j, k}));
  return v;
}

double radiusOf(const Volume& v) { return 0.5 * glm::length(glm::dvec3(v.dimensions()) * v.spacing()); }

TEST(Raycast, MipAlongTheSliceAxisEqualsTheCtMaximumProjection) {
  const Volume ct = io::readVolume(test::sampleData("cranium/cranium.nii.gz"));
  const glm::ivec3 d = ct.dimensions();
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, ct);
  RenderSettings s;
  s.mode = RenderMode::Mip;
  s.size = {d.x, d.y};
  // Superior view: screen right = patient right (-x, i decreasing), screen down = +y (j).
  s.camera.view = StandardView::Superior;
  s.camera.zoom = radiusOf(ct) / (0.5 * d.y * ct.spacing().y);  // one pixel per voxel
  s.jitter = false;
  s.stepMm = ct.spacing().z;  // with midpoint sampling every sample is a voxel centre
  const Frame f = renderer.render(s);
  const auto [lo, hi] = ct.valueRange();
  double mse = 0.0;
  int worst = 0;
  for (int r = 0; r < d.y; ++r)
    for (int c = 0; c < d.x; ++c) {
      const int i = d.x - 1 - c, j = r;
      double m = -1e30;
      for (int k = 0; k < d.z; ++k) m = std::max(m, ct.value(i, j, k));
      const double expected = std::clamp((m - lo) / (hi - lo), 0.0, 1.0) * 255.0;
      const double got = f.image.pixel(c, r)[0];
      mse += (got - expected) * (got - expected);
      worst = std::max(worst, static_cast<int>(std::abs(got - expected) + 0.5));
    }
  mse /= d.x * d.y;
  const double psnr = 10.0 * std::log10(255.0 * 255.0 / std::max(mse, 1e-12));
  std::cout << "MIP vs max projection: PSNR " << psnr << " dB, worst pixel " << worst << "/255\n";
  EXPECT_GE(psnr, 35.0);
  EXPECT_LE(worst, 2);
}

TEST(Raycast, IsosurfaceBisectionFindsTheSphereWithinATenthOfAVoxel) {
  // Value = R - distance to the centre: the 0-isosurface is the sphere of radius R.
  const double R = 20.0;
  const glm::dmat4 w = makeWorldFromIndex({-32, -32, -24}, {1.0, 1.0, 1.5}, glm::dmat3(1.0));
  const glm::dvec3 centre(0.0, 0.0, 0.0);
  const Volume v = makeVolume({65, 65, 33}, w, [&](glm::dvec3 p) { return static_cast<float>(R - glm::length(p - centre)); });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Isosurface;
  s.isoValue = 0.0;
  s.size = {65, 65};  // odd: the middle pixel's ray passes through the centre
  s.camera.zoom = 2.5;  // about 0.7 mm per pixel
  s.jitter = false;
  const Frame f = renderer.render(s);
  double worstErr = 0.0;
  int checked = 0;
  for (int r = 0; r < 65; ++r)
    for (int c = 0; c < 65; ++c) {
      const glm::dvec2 ndc((c + 0.5) / 65 * 2 - 1, 1 - (r + 0.5) / 65 * 2);
      const WorldRay ray = rayThrough(f.camera, ndc);
      const glm::dvec3 origin = ray.origin, dir = ray.direction;
      const double along = glm::dot(centre - origin, dir);
      const double rho2 = glm::dot(centre - origin, centre - origin) - along * along;
      if (rho2 > (0.9 * R) * (0.9 * R)) continue;
      const double expected = along - std::sqrt(R * R - rho2);
      const double got = f.image.depth[static_cast<std::size_t>(r) * 65 + c];
      worstErr = std::max(worstErr, std::abs(got - expected));
      ++checked;
    }
  std::cout << "isosurface: worst distance error " << worstErr << " mm over " << checked << " rays\n";
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worstErr, 0.1);  // voxels are >= 1 mm: below a tenth of a voxel
}

TEST(Raycast, CompositeThroughAUniformSlabFollowsBeerLambert) {
  // 16 mm of a medium with opacity 0.1 per 1 mm reference step: T = 0.9^16.
  const Volume v = makeVolume({32, 32, 16}, makeWorldFromIndex({0, 0, 0}, {1, 1, 1}, glm::dmat3(1.0)),
                              [](glm::dvec3) { return 100.0f; });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Composite;
  s.transfer = TransferFunction{"flat", false, {TfPoint{0, {1, 1, 1, 0.1f}}, TfPoint{200, {1, 1, 1, 0.1f}}}};
  s.shading = false;
  s.jitter = false;
  s.camera.view = StandardView::Superior;
  s.size = {33, 33};
  for (double step : {0.5, 0.25, 1.0 / 3.0}) {
    s.stepMm = step;
    const Frame f = renderer.render(s);
    const double expected = (1.0 - std::pow(0.9, 16.0)) * 255.0;
    EXPECT_NEAR(f.image.pixel(16, 16)[0], expected, 1.0) << "step " << step;
  }
}

// A dark cube with bright markers 15 mm toward the patient's left, posterior and superior.
float markers(glm::dvec3 p) {
  auto near = [&](glm::dvec3 c) { return glm::length(p - c) < 4.0; };
  if (near({15, 0, 0})) return 1000.0f;  // L
  if (near({0, 15, 0})) return 600.0f;   // P
  if (near({0, 0, 15})) return 300.0f;   // S
  return 0.0f;
}

struct Centroid {
  double x = 0, y = 0;
  int n = 0;
};
// Centroid of the pixels whose red channel lies in [lo, hi].
Centroid centroidOf(const Image& img, int lo, int hi) {
  Centroid c;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const int g = img.pixel(x, y)[0];
      if (g >= lo && g <= hi) {
        c.x += x;
        c.y += y;
        ++c.n;
      }
    }
  if (c.n) {
    c.x /= c.n;
    c.y /= c.n;
  }
  return c;
}

TEST(Raycast, MarkersAppearWhereTheOrientationLabelsSayForAnyStorageOrder) {
  // The same world content stored in LPS order and in RAS order (flipped i and j).
  const glm::ivec3 d(41, 41, 41);
  const Volume lps = makeVolume(d, makeWorldFromIndex({-20, -20, -20}, {1, 1, 1}, glm::dmat3(1.0)), markers);
  const Volume ras = makeVolume(
      d, makeWorldFromIndex({20, 20, -20}, {1, 1, 1}, glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1))),
      markers);
  auto ctx = createHeadlessContext({16, 16});
  for (const Volume* v : {&lps, &ras}) {
    VolumeRenderer renderer(*ctx, *v);
    RenderSettings s;
    s.mode = RenderMode::Mip;
    s.size = {101, 101};
    s.window = 1000;
    s.level = 500;
    s.jitter = false;
    s.linear = false;  // nearest: marker edges keep their exact grey (255, 153, 76)
    s.camera.view = StandardView::Anterior;  // screen right = patient left, up = superior
    Frame f = renderer.render(s);
    const Centroid left = centroidOf(f.image, 250, 255), sup = centroidOf(f.image, 70, 82);
    ASSERT_GT(left.n, 10);
    ASSERT_GT(sup.n, 10);
    EXPECT_GT(left.x, 65);              // L marker on the right half
    EXPECT_NEAR(left.y, 50, 3);
    EXPECT_LT(sup.y, 35);               // S marker at the top
    EXPECT_NEAR(sup.x, 50, 3);
    s.camera.view = StandardView::Left;  // screen right = posterior
    f = renderer.render(s);
    const Centroid post = centroidOf(f.image, 148, 158);
    ASSERT_GT(post.n, 10);
    EXPECT_GT(post.x, 65);
    EXPECT_NEAR(post.y, 50, 3);
  }
}

TEST(Raycast, RenderingTwiceGivesIdenticalPixels) {
  const Volume v = makeVolume({30, 20, 10}, makeWorldFromIndex({0, 0, 0}, {1, 1.5, 2}, glm::dmat3(1.0)),
                              [](glm::dvec3 p) { return static_cast<float>(p.x * 10 + p.y * 3 + p.z); });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.transfer = transferPreset("mr-default");
  s.camera.azimuthDeg = 30;
  s.camera.elevationDeg = 20;
  s.size = {47, 31};
  const Frame a = renderer.render(s), b = renderer.render(s);
  EXPECT_EQ(a.image.rgba, b.image.rgba);
  s.seed = 2;
  const Frame c = renderer.render(s);
  EXPECT_NE(a.image.rgba, c.image.rgba);  // the jitter follows the seed
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

TEST(Mpr, AxialPlaneShowsTheMiddleSliceVoxelForVoxel) {
  // value = 100 k + 3 j + i: every voxel distinct. Odd slice count: the plane through the
  // centre lies on slice 12's voxel centres.
  const glm::ivec3 d(40, 30, 25);
  const Volume v = makeVolume(d, makeWorldFromIndex({0, 0, 0}, {1, 1, 2}, glm::dmat3(1.0)), [](glm::dvec3 p) {
    return static_cast<float>(100 * std::lround(p.z / 2) + 3 * std::lround(p.y) + std::lround(p.x));
  });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Mpr;
  s.camera.view = *parseStandardView("axial");  // from the feet: screen right = +x, down = +y
  s.size = {d.x, d.y};
  s.camera.zoom = radiusOf(v) / (0.5 * d.y);  // one pixel per voxel
  s.window = 256;
  s.level = 1200 + 128;  // slice 12 holds 1200 .. 1200 + 3*29 + 39
  const Frame f = renderer.render(s);
  for (int r = 0; r < d.y; ++r)
    for (int c = 0; c < d.x; ++c) {
      const double expected = (1200 + 3 * r + c) - 1200.0;  // grey = value - (level - window/2)
      ASSERT_NEAR(f.image.pixel(c, r)[0], expected, 1.0) << c << "," << r;
    }
  // A 10 mm slab MIP around z = 24 mm: midpoint samples every 0.5 mm, the deepest at
  // z = 28.75 mm = slice 14.375, where the (linear in z) value is 1437.5 + 3 j + i.
  s.slabMm = 10.0;
  s.level = 1400 + 128;
  const Frame slab = renderer.render(s);
  EXPECT_NEAR(slab.image.pixel(5, 7)[0], (1437.5 + 21 + 5) - 1400.0, 1.0);
}

TEST(Mpr, FunctionalOverlayFollowsTheRegistrationTransform) {
  const Volume anatomy = makeVolume({41, 41, 21}, makeWorldFromIndex({-20, -20, -10}, {1, 1, 1}, glm::dmat3(1.0)),
                                    [](glm::dvec3) { return 0.0f; });
  // A hot 8 mm cube at the functional origin, on a coarse 4 mm grid.
  const Volume hot = makeVolume({11, 11, 11}, makeWorldFromIndex({-20, -20, -20}, {4, 4, 4}, glm::dmat3(1.0)),
                                [](glm::dvec3 p) { return glm::all(glm::lessThan(glm::abs(p), glm::dvec3(4.1))) ? 10.0f : 0.0f; });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, anatomy);
  RenderSettings s;
  s.mode = RenderMode::Mpr;
  s.camera.view = StandardView::Inferior;
  s.size = {41, 41};
  s.camera.zoom = radiusOf(anatomy) / 20.5;
  s.window = 100;
  s.level = 50;
  s.overlayOpacity = 1.0f;
  s.overlayThreshold = 0.5f;
  auto hotCentroid = [](const Image& img) { return centroidOf(img, 129, 255); };
  renderer.setFunctional(hot, glm::dmat4(1.0));
  const Centroid at = hotCentroid(renderer.render(s).image);
  ASSERT_GT(at.n, 20);
  EXPECT_NEAR(at.x, 20, 1.0);
  EXPECT_NEAR(at.y, 20, 1.0);
  // anatomicalFromFunctional moves the functional volume 10 mm toward the patient's left
  // (+x): on the axial view (screen right = +x at one pixel per mm) 10 pixels right.
  glm::dmat4 shift(1.0);
  shift[3] = glm::dvec4(10, 0, 0, 1);
  renderer.setFunctional(hot, shift);
  const Centroid moved = hotCentroid(renderer.render(s).image);
  ASSERT_GT(moved.n, 20);
  EXPECT_NEAR(moved.x, 30, 1.0);
  EXPECT_NEAR(moved.y, 20, 1.0);
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

// Two spheres one behind the other as seen from the front: a dim one (600) near the viewer
// (anterior, -y) and a bright one (800) far behind it.
float nearDimFarBright(glm::dvec3 p) {
  if (glm::length(p - glm::dvec3(0, -20, 0)) < 8.0) return 600.0f;
  if (glm::length(p - glm::dvec3(0, 20, 0)) < 8.0) return 800.0f;
  return 0.0f;
}

TEST(DepthCuedMip, NeutralSettingsReproducePlainMipExactly) {
  const Volume v = makeVolume({41, 51, 31}, makeWorldFromIndex({-20, -25, -15}, {1, 1, 1}, glm::dmat3(1.0)),
                              [](glm::dvec3 p) { return static_cast<float>(nearDimFarBright(p) + 30 * std::sin(p.x * 0.3) + p.z); });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Mip;
  s.size = {63, 47};
  s.window = 900;
  s.level = 400;
  s.camera.azimuthDeg = 20;
  const Frame plain = renderer.render(s);
  s.depthCue = true;  // contrast 100 %, depth cue 0, brightness 0
  const Frame neutral = renderer.render(s);
  EXPECT_EQ(plain.image.rgba, neutral.image.rgba);
}

TEST(DepthCuedMip, TheRampIsAppliedBeforeTheMaximum) {
  const Volume v = makeVolume({41, 61, 41}, makeWorldFromIndex({-20, -30, -20}, {1, 1, 1}, glm::dmat3(1.0)), nearDimFarBright);
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Mip;
  s.size = {41, 41};  // odd: the middle ray passes through both centres
  s.window = 1000;
  s.level = 500;  // emission = value / 1000
  s.jitter = false;
  s.linear = false;
  s.camera.view = StandardView::Anterior;
  const Frame plain = renderer.render(s);
  EXPECT_NEAR(plain.image.pixel(20, 20)[0], 0.8 * 255, 1.0);  // the bright far sphere wins
  s.depthCue = true;
  s.cueBrightness = 0.0;
  s.cueAmount = 1.0;  // beta = z: 1 at the image side of the bounding sphere, 0 behind it
  s.cueContrast = 0.0;
  const Frame cued = renderer.render(s);
  // Along the middle ray z = 1 - (t - tFront) / 2R with R the bounding sphere's radius; the
  // spheres' front surfaces lie at y = -28 and y = 12, i.e. R - 28 and R + 12 mm behind tFront.
  const double R = radiusOf(v);
  const double zNear = 1.0 - (R - 28.0) / (2.0 * R), zFar = 1.0 - (R + 12.0) / (2.0 * R);
  const double expected = std::max(zNear * 0.6, zFar * 0.8);
  ASSERT_GT(zNear * 0.6, zFar * 0.8) << "the phantom must show the inversion";
  EXPECT_NEAR(cued.image.pixel(20, 20)[0], expected * 255.0, 3.0);
  // The depth channel reports where the maximum was taken: the near sphere's front.
  const double tFront = glm::dot(-rayThrough(cued.camera, {0, 0}).origin, cued.camera.forward) - R;
  EXPECT_NEAR(cued.image.depth[20 * 41 + 20], tFront + (R - 28.0), 1.0);
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

// A sphere (radius 25 mm) seen as an isosurface, and a functional attribute that is zero
// on the patient's right (x < 0) and `level` on the left (x > 0).
struct GlyphScene {
  Volume anatomy = makeVolume({61, 61, 61}, makeWorldFromIndex({-30, -30, -30}, {1, 1, 1}, glm::dmat3(1.0)),
                              [](glm::dvec3 p) { return static_cast<float>(25.0 - glm::length(p)); });
  // An isosurface of the sphere, seen from the front (screen right = patient left = +x),
  // glyphs on, the attribute mapped 0..1, many glyphs (4 mm) over the 50 mm sphere.
  static RenderSettings settings() {
    RenderSettings s;
    s.mode = RenderMode::Isosurface;
    s.isoValue = 0.0;
    s.size = {241, 241};
    s.jitter = false;
    s.camera.view = StandardView::Anterior;
    s.glyphs = true;
    s.glyphDiameterMm = 4.0;
    s.functionalLow = 0.0;
    s.functionalHigh = 1.0;
    return s;
  }
  static Volume attribute(float level) {
    return makeVolume({16, 16, 16}, makeWorldFromIndex({-30, -30, -30}, {4, 4, 4}, glm::dmat3(1.0)),
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
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, scene.anatomy);
  RenderSettings s = GlyphScene::settings();
  s.glyphs = false;
  const Frame plain = renderer.render(s);
  // beta = 0 everywhere: bit for bit the plain image.
  renderer.setFunctional(GlyphScene::attribute(0.0f), glm::dmat4(1.0));
  s.glyphs = true;
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
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, scene.anatomy);
  RenderSettings s = GlyphScene::settings();
  const Frame plain = [&] {
    RenderSettings p = s;
    p.glyphs = false;
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
  const Frame bumps = renderer.render(s);
  s.glyphConvexity = GlyphConvexity::Dimples;
  const Frame dimples = renderer.render(s);
  EXPECT_GT(changedPixels(bumps.image, dimples.image), previous / 2);
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

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
  const Volume slab = makeVolume({81, 81, 81}, makeWorldFromIndex(origin, {1, 1, 1}, glm::dmat3(1.0)),
                                 [face](glm::dvec3 p) { return static_cast<float>(p.y - face); });
  const Volume attribute = makeVolume({9, 9, 9}, makeWorldFromIndex(origin, {10, 10, 10}, glm::dmat3(1.0)),
                                      [](glm::dvec3) { return 1.0f; });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, slab);
  renderer.setFunctional(attribute, glm::dmat4(1.0));
  RenderSettings s;
  s.mode = RenderMode::Isosurface;
  s.isoValue = 0.0;
  s.size = {161, 161};
  s.jitter = false;
  s.camera.view = StandardView::Anterior;  // screen right = +x, up = +z
  s.camera.zoom = radiusOf(slab) / 40.5;  // 0.5 mm per pixel over the 80 mm slab
  s.glyphs = true;
  s.glyphMap = one;
  s.glyphDiameterMm = 2 * R;
  s.functionalLow = 0.0;
  s.functionalHigh = 1.0;
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
  s.glyphConvexity = GlyphConvexity::Bumps;
  const auto [bumpLeft, bumpRight] = sides(renderer.render(s).image);
  s.glyphConvexity = GlyphConvexity::Dimples;
  const auto [dimpleLeft, dimpleRight] = sides(renderer.render(s).image);
  std::cout << "bump left/right " << bumpLeft << "/" << bumpRight << ", dimple " << dimpleLeft << "/"
            << dimpleRight << "\n";
  EXPECT_GT(bumpLeft, bumpRight + 10);
  EXPECT_GT(dimpleRight, dimpleLeft + 10);
}

TEST(DepthCuedMip, IdenticalBlobsAreDimmedByTheRampRatio) {
  // Two identical bright blobs side by side on screen, one 30 mm nearer than the other.
  auto blobs = [](glm::dvec3 p) {
    if (glm::length(p - glm::dvec3(-12, -15, 0)) < 5.0) return 900.0f;  // near (anterior)
    if (glm::length(p - glm::dvec3(12, 15, 0)) < 5.0) return 900.0f;    // far
    return 0.0f;
  };
  const Volume v = makeVolume({61, 61, 41}, makeWorldFromIndex({-30, -30, -20}, {1, 1, 1}, glm::dmat3(1.0)), blobs);
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Mip;
  s.size = {121, 121};
  s.window = 1000;
  s.level = 500;
  s.jitter = false;
  s.linear = false;
  s.depthCue = true;
  s.cueAmount = 1.0;
  s.cueContrast = 0.0;
  const Frame f = renderer.render(s);
  // The brightest pixel of each blob: its front point, 5 mm before the centre.
  auto brightest = [&](int x0, int x1) {
    int best = 0;
    for (int y = 0; y < 121; ++y)
      for (int x = x0; x < x1; ++x) best = std::max<int>(best, f.image.pixel(x, y)[0]);
    return best;
  };
  const int nearPeak = brightest(0, 60), farPeak = brightest(61, 121);
  const double R = radiusOf(v);
  // z of a point at depth y (mm along +y, the anterior view's line of sight) through the
  // volume centre: 1 at y = -R, 0 at y = +R.
  const double zNear = 1.0 - ((-15.0 - 5.0) + R) / (2.0 * R), zFar = 1.0 - ((15.0 - 5.0) + R) / (2.0 * R);
  std::cout << "near " << nearPeak << " far " << farPeak << " expected ratio " << zFar / zNear << "\n";
  EXPECT_NEAR(nearPeak, 0.9 * zNear * 255, 3.0);
  EXPECT_NEAR(farPeak, 0.9 * zFar * 255, 3.0);
  EXPECT_NEAR(static_cast<double>(farPeak) / nearPeak, zFar / zNear, 0.03);
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

TEST(DepthCuedMip, OverlappingVesselsShowTheNearerOne) {
  VesselTreeSettings vs;
  vs.dimensions = {96, 96, 96};
  vs.noiseSigma = 0.0;  // equal brightness everywhere in the vessels: only depth decides
  vs.background = 0.0;
  vs.seed = 3;
  vs.generations = 6;
  vs.rootLengthMm = 30.0;
  const VesselTree tree = makeVesselTree(vs);
  ASSERT_EQ(tree.segments.size(), 63u);  // 1 + 2 + 4 + 8 + 16 + 32
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, tree.volume);
  RenderSettings s;
  s.mode = RenderMode::Mip;
  s.size = {128, 128};
  s.window = 1000;
  s.level = 500;
  s.jitter = false;
  s.depthCue = true;
  s.cueAmount = 1.0;
  s.cueContrast = 0.0;
  int overlaps = 0, nearest = 0;
  for (StandardView view : {StandardView::Anterior, StandardView::Left, StandardView::Superior}) {
  s.camera.view = view;
  const Frame f = renderer.render(s);
  // March each pixel's ray through the analytic tubes and find the runs of "inside a
  // tube's core" along it. Where two separate runs lie on a ray (two vessels one behind the
  // other), the reported depth of the maximum must fall in the first, nearer run.
  for (int r = 0; r < 128; ++r)
    for (int c = 0; c < 128; ++c) {
      const glm::dvec2 ndc((c + 0.5) / 128 * 2 - 1, 1 - (r + 0.5) / 128 * 2);
      const WorldRay ray = rayThrough(f.camera, ndc);
      const glm::dvec3 o = ray.origin, dir = ray.direction;
      // The far end of the projector, where the march stops.
      const glm::dvec4 e4 = f.camera.worldFromClip * glm::dvec4(ndc, 1, 1);
      std::vector<std::pair<double, double>> runs;
      std::vector<double> runRadius;  // the thickest tube in each run
      bool in = false;
      for (double t = 0; t < glm::length(glm::dvec3(e4) / e4.w - o); t += 0.5) {
        const glm::dvec3 p = o + t * dir;
        bool core = false;
        double radius = 0.0;
        for (const auto& sg : tree.segments) {
          const glm::dvec3 ab = sg.to - sg.from;
          const double u = std::clamp(glm::dot(p - sg.from, ab) / glm::dot(ab, ab), 0.0, 1.0);
          if (glm::length(p - (sg.from + u * ab)) <= sg.radiusMm - 0.5) {
            core = true;
            radius = std::max(radius, sg.radiusMm);
          }
        }
        if (core && !in) {
          runs.push_back({t, t});
          runRadius.push_back(0.0);
        }
        if (core) {
          runs.back().second = t;
          runRadius.back() = std::max(runRadius.back(), radius);
        }
        in = core;
      }
      // Two runs separated by at least 3 mm of background: two vessels. The near one must be
      // thick enough to reach full brightness through the trilinear partial volume (radius
      // >= 1.5 mm) and the ray must pass through its core, not graze it: a thin or grazed
      // vessel is legitimately dimmer, and eq. (3) may then pick the far one.
      if (runs.size() < 2 || runs[1].first - runs[0].second < 3.0 || runs[0].second - runs[0].first < 2.5 ||
          runRadius[0] < 1.5)
        continue;
      ++overlaps;
      const float reported = f.image.depth[static_cast<std::size_t>(r) * 128 + c];
      if (reported >= runs[0].first - 1.0 && reported <= runs[0].second + 1.0) ++nearest;
      else std::cout << "  not nearest: view " << toString(view) << " ray " << c << "," << r << ": reported " << reported
                     << ", runs " << runs[0].first << ".." << runs[0].second << " (r " << runRadius[0] << ") and "
                     << runs[1].first << ".." << runs[1].second << " (r " << runRadius[1] << "), grey "
                     << int(f.image.pixel(c, r)[0]) << "\n";
    }
  }
  std::cout << overlaps << " overlapping rays, nearest reported on " << nearest << "\n";
  ASSERT_GE(overlaps, 10);
  EXPECT_EQ(nearest, overlaps);
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

TEST(Shells, DiscreteMaximumConvergesToTheRayCastAsShellsAreAdded) {
  VesselTreeSettings vs;
  vs.dimensions = {80, 80, 80};
  vs.noiseSigma = 0.0;
  vs.seed = 5;
  const VesselTree tree = makeVesselTree(vs);
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, tree.volume);
  RenderSettings s;
  s.size = {96, 96};
  s.window = 1000;
  s.level = 500;
  s.jitter = false;
  s.stepMm = 0.25;
  s.depthCue = true;
  s.cueAmount = 0.66;
  s.cueContrast = 0.33;
  s.camera.azimuthDeg = 30;
  s.mode = RenderMode::Mip;
  const Frame reference = renderer.render(s);
  s.mode = RenderMode::ShellMip;
  double previous = 1e9;
  for (int n : {4, 8, 16, 32}) {
    s.shellCount = n;
    const Frame f = renderer.render(s);
    double err = 0.0;
    for (std::size_t i = 0; i < f.image.rgba.size(); i += 4)
      err += std::abs(double(f.image.rgba[i]) - double(reference.image.rgba[i]));
    err /= f.image.rgba.size() / 4;
    std::cout << n << " shells: mean |error| " << err << " / 255 against the ray cast\n";
    EXPECT_LT(err, previous) << n << " shells";
    previous = err;
  }
  EXPECT_LT(previous, 3.0);  // 32 shells: within a few grey levels on average
}

TEST(Shells, DisabledShellsAreNotDrawnAndLitShellsShowTheOutermost) {
  const Volume v = makeVolume({41, 41, 41}, makeWorldFromIndex({-20, -20, -20}, {1, 1, 1}, glm::dmat3(1.0)),
                              [](glm::dvec3 p) { return static_cast<float>(std::max(0.0, 1000.0 - 50.0 * glm::length(p))); });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::ShellMip;
  s.size = {41, 41};
  s.window = 1000;
  s.level = 500;
  s.shellCount = 4;  // spheres at 250, 500, 750, 1000 -> radii 15, 10, 5, 0 mm
  const Frame all = renderer.render(s);
  EXPECT_NEAR(all.image.pixel(20, 20)[0], 0.75 * 255, 1.0);  // without depth cue: the brightest shell drawn (1000 is a point)
  s.shellEnabled = {true, true, false, false};
  const Frame two = renderer.render(s);
  EXPECT_NEAR(two.image.pixel(20, 20)[0], 0.5 * 255, 1.0);
  s.mode = RenderMode::ShellLit;
  s.shellEnabled.clear();
  const Frame lit = renderer.render(s);
  // The outermost shell (emission 0.25, radius 15 mm) hides the others: its rim is lit.
  EXPECT_GT(lit.image.pixel(20, 20)[0], 0);
  EXPECT_LE(lit.image.pixel(20, 20)[0], std::lround(0.25 * (0.25 + 0.7) * 255 + 0.25 * 255) + 1);
}

}  // namespace
}  // namespace mvw::render

namespace mvw::render {
namespace {

// Seipel's claim for DVR: the glyphs stay visible while the opacity transfer function is
// lowered. The distance-field sphere in composite DVR, its opacity per step scaled from
// surface-like (0.9) to faint (0.05); the attribute on the right half. At every opacity the
// glyphs change a similar share of the sphere's pixels, visibly, and never the left half.
TEST(Glyphs, StayVisibleInCompositeDvrAsTheOpacityIsLowered) {
  GlyphScene scene;
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, scene.anatomy);
  renderer.setFunctional(GlyphScene::attribute(0.8f), glm::dmat4(1.0));
  RenderSettings s = GlyphScene::settings();
  s.mode = RenderMode::Composite;
  s.lightOffset = {-0.8, 0.8};
  std::vector<double> shares, contrasts;
  for (double opacity : {0.9, 0.3, 0.1, 0.05}) {
    const glm::vec3 c(0.9f, 0.85f, 0.8f);
    s.transfer = {"step", false, {{-0.5, glm::vec4(c, 0.0f)}, {0.5, glm::vec4(c, float(opacity))}}};
    s.glyphs = false;
    const Image plain = renderer.render(s).image;
    s.glyphs = true;
    const Image glyphs = renderer.render(s).image;
    int sphere = 0, changed = 0, wrongSide = 0;
    double delta = 0.0, level = 0.0;
    for (int y = 0; y < plain.height; ++y)
      for (int x = 0; x < plain.width; ++x) {
        const auto* p = plain.pixel(x, y);
        const auto* q = glyphs.pixel(x, y);
        const int d = std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])});
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
    std::cout << "opacity " << opacity << ": " << 100.0 * share << " % of the sphere's right half changed by > 4, "
              << "mean change " << 100.0 * contrast << " % of its brightness\n";
    EXPECT_EQ(wrongSide, 0) << "opacity " << opacity;
    shares.push_back(share);
    contrasts.push_back(contrast);
    // Measured on llvmpipe: 7.9, 13.0, 13.0, 8.0 % of the pixels; 2.2, 2.2, 1.7, 1.2 %.
    EXPECT_GT(share, 0.04) << "opacity " << opacity;
    EXPECT_GT(contrast, 0.008) << "opacity " << opacity;
  }
  EXPECT_GT(shares.back(), 0.5 * shares.front());
}

}  // namespace
}  // namespace mvw::render
