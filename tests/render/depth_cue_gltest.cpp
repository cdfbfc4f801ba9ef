// MIP with depth cueing (Heidrich et al. 1995, eq. 3): neutral settings are plain MIP, the
// ramp is applied before the maximum, identical blobs dim by the ramp ratio, and of two
// overlapping vessels the nearer one is reported.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/core/VesselPhantom.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

// Two spheres one behind the other as seen from the front: a dim one (600) near the viewer
// (anterior, -y) and a bright one (800) far behind it.
float nearDimFarBright(glm::dvec3 p) {
  if (glm::length(p - glm::dvec3(0, -20, 0)) < 8.0) return 600.0f;
  if (glm::length(p - glm::dvec3(0, 20, 0)) < 8.0) return 800.0f;
  return 0.0f;
}

TEST(DepthCuedMip, NeutralSettingsReproducePlainMipExactly) {
  const Volume v =
      makeVolume({41, 51, 31}, test::axisGrid({-20, -25, -15}, {1, 1, 1}), [](glm::dvec3 p) {
        return static_cast<float>(nearDimFarBright(p) + 30 * std::sin(p.x * 0.3) + p.z);
      });
  test::Renderer renderer(v);
  RenderSettings s = test::settingsOf({.mode = RenderMode::Mip, .size = {63, 47}});
  s.window = {900, 400};
  s.camera.azimuthDeg = 20;
  const RenderedFrame plain = renderer.render(s);
  s.depthCue.on = true;  // contrast 100 %, depth cue 0, brightness 0
  const RenderedFrame neutral = renderer.render(s);
  EXPECT_EQ(plain.image.rgba, neutral.image.rgba);
}

TEST(DepthCuedMip, TheRampIsAppliedBeforeTheMaximum) {
  const Volume v =
      makeVolume({41, 61, 41}, test::axisGrid({-20, -30, -20}, {1, 1, 1}), nearDimFarBright);
  test::Renderer renderer(v);
  RenderSettings s = test::settingsOf({
      .mode = RenderMode::Mip,
      .size = {41, 41},  // odd: the middle ray passes through both centres
      .view = StandardView::Anterior,
      .jitterOff = true,
  });
  s.window = {1000, 500};  // emission = value / 1000
  s.linear = false;
  const RenderedFrame plain = renderer.render(s);
  EXPECT_NEAR(plain.image.pixel(20, 20)[0], 0.8 * 255, 1.0);  // the bright far sphere wins
  s.depthCue.on = true;
  s.depthCue.brightness = 0.0;
  s.depthCue.amount = 1.0;  // beta = z: 1 at the image side of the bounding sphere, 0 behind it
  s.depthCue.contrast = 0.0;
  const RenderedFrame cued = renderer.render(s);
  // Along the middle ray z = 1 - (t - tFront) / 2R with R the bounding sphere's radius; the
  // spheres' front surfaces lie at y = -28 and y = 12, i.e. R - 28 and R + 12 mm behind tFront.
  const double R = framingSphere(v).radius;
  const double zNear = 1.0 - (R - 28.0) / (2.0 * R), zFar = 1.0 - (R + 12.0) / (2.0 * R);
  const double expected = std::max(zNear * 0.6, zFar * 0.8);
  ASSERT_GT(zNear * 0.6, zFar * 0.8) << "the phantom must show the inversion";
  EXPECT_NEAR(cued.image.pixel(20, 20)[0], expected * 255.0, 3.0);
  // The depth channel reports where the maximum was taken: the near sphere's front.
  const double tFront = glm::dot(-rayThrough(cued.camera, {0, 0}).origin, cued.camera.forward) - R;
  EXPECT_NEAR(cued.image.depth[20 * 41 + 20], tFront + (R - 28.0), 1.0);
}

TEST(DepthCuedMip, IdenticalBlobsAreDimmedByTheRampRatio) {
  // Two identical bright blobs side by side on screen, one 30 mm nearer than the other.
  auto blobs = [](glm::dvec3 p) {
    if (glm::length(p - glm::dvec3(-12, -15, 0)) < 5.0) return 900.0f;  // near (anterior)
    if (glm::length(p - glm::dvec3(12, 15, 0)) < 5.0) return 900.0f;    // far
    return 0.0f;
  };
  const Volume v = makeVolume({61, 61, 41}, test::axisGrid({-30, -30, -20}, {1, 1, 1}), blobs);
  test::Renderer renderer(v);
  RenderSettings s =
      test::settingsOf({.mode = RenderMode::Mip, .size = {121, 121}, .jitterOff = true});
  s.window = {1000, 500};
  s.linear = false;
  s.depthCue.on = true;
  s.depthCue.amount = 1.0;
  s.depthCue.contrast = 0.0;
  const RenderedFrame f = renderer.render(s);
  // The brightest pixel of each blob: its front point, 5 mm before the centre.
  auto brightest = [&](int x0, int x1) {
    int best = 0;
    for (int y = 0; y < 121; ++y)
      for (int x = x0; x < x1; ++x) best = std::max<int>(best, f.image.pixel(x, y)[0]);
    return best;
  };
  const int nearPeak = brightest(0, 60), farPeak = brightest(61, 121);
  const double R = framingSphere(v).radius;
  // z of a point at depth y (mm along +y, the anterior view's line of sight) through the
  // volume centre: 1 at y = -R, 0 at y = +R.
  const double zNear = 1.0 - ((-15.0 - 5.0) + R) / (2.0 * R),
               zFar = 1.0 - ((15.0 - 5.0) + R) / (2.0 * R);
  std::cout << "near " << nearPeak << " far " << farPeak << " expected ratio " << zFar / zNear
            << "\n";
  EXPECT_NEAR(nearPeak, 0.9 * zNear * 255, 3.0);
  EXPECT_NEAR(farPeak, 0.9 * zFar * 255, 3.0);
  EXPECT_NEAR(static_cast<double>(farPeak) / nearPeak, zFar / zNear, 0.03);
}

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
  test::Renderer renderer(tree.volume);
  RenderSettings s =
      test::settingsOf({.mode = RenderMode::Mip, .size = {128, 128}, .jitterOff = true});
  s.window = {1000, 500};
  s.depthCue.on = true;
  s.depthCue.amount = 1.0;
  s.depthCue.contrast = 0.0;
  int overlaps = 0, nearest = 0;
  for (StandardView view : {StandardView::Anterior, StandardView::Left, StandardView::Superior}) {
    s.camera.view = view;
    const RenderedFrame f = renderer.render(s);
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
        if (runs.size() < 2 || runs[1].first - runs[0].second < 3.0 ||
            runs[0].second - runs[0].first < 2.5 || runRadius[0] < 1.5)
          continue;
        ++overlaps;
        const float reported = f.image.depth[static_cast<std::size_t>(r) * 128 + c];
        if (reported >= runs[0].first - 1.0 && reported <= runs[0].second + 1.0)
          ++nearest;
        else
          std::cout << "  not nearest: view " << toString(view) << " ray " << c << "," << r
                    << ": reported " << reported << ", runs " << runs[0].first << ".."
                    << runs[0].second << " (r " << runRadius[0] << ") and " << runs[1].first << ".."
                    << runs[1].second << " (r " << runRadius[1] << "), grey "
                    << int(f.image.pixel(c, r)[0]) << "\n";
      }
  }
  std::cout << overlaps << " overlapping rays, nearest reported on " << nearest << "\n";
  ASSERT_GE(overlaps, 10);
  EXPECT_EQ(nearest, overlaps);
}

}  // namespace
}  // namespace mvw::render
