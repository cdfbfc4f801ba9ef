// Composite DVR: Beer-Lambert through a uniform slab at any step, and frames that repeat
// exactly (and follow the jitter seed).
#include <cmath>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

TEST(Raycast, CompositeThroughAUniformSlabFollowsBeerLambert) {
  // 16 mm of a medium with opacity 0.1 per 1 mm reference step: T = 0.9^16.
  const Volume v =
      makeVolume({32, 32, 16}, makeWorldFromIndex({0, 0, 0}, {1, 1, 1}, glm::dmat3(1.0)),
                 [](glm::dvec3) { return 100.0f; });
  auto ctx = createHeadlessContext({16, 16});
  VolumeRenderer renderer(*ctx, v);
  RenderSettings s;
  s.mode = RenderMode::Composite;
  s.transfer =
      TransferFunction{"flat", false, {TfPoint{0, {1, 1, 1, 0.1f}}, TfPoint{200, {1, 1, 1, 0.1f}}}};
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

TEST(Raycast, RenderingTwiceGivesIdenticalPixels) {
  const Volume v =
      makeVolume({30, 20, 10}, makeWorldFromIndex({0, 0, 0}, {1, 1.5, 2}, glm::dmat3(1.0)),
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
