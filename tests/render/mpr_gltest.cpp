// MPR: the axial plane voxel for voxel, a thick slab's maximum, and the functional overlay
// where the registration transform puts it.
#include <cmath>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::Centroid;
using test::centroidOf;
using test::makeVolume;

TEST(Mpr, AxialPlaneShowsTheMiddleSliceVoxelForVoxel) {
  // value = 100 k + 3 j + i: every voxel distinct. Odd slice count: the plane through the
  // centre lies on slice 12's voxel centres.
  const glm::ivec3 d(40, 30, 25);
  const Volume v = makeVolume(d, test::axisGrid({0, 0, 0}, {1, 1, 2}), [](glm::dvec3 p) {
    return static_cast<float>(100 * std::lround(p.z / 2) + 3 * std::lround(p.y) + std::lround(p.x));
  });
  test::Renderer renderer(v);
  RenderSettings s = test::settingsOf({
      .mode = RenderMode::Mpr,
      .size = {d.x, d.y},
      .view = *parseStandardView("axial"),  // from the feet: screen right = +x, down = +y
  });
  s.camera.zoom = framingSphere(v).radius / (0.5 * d.y);  // one pixel per voxel
  // Slice 12 holds 1200 .. 1200 + 3*29 + 39.
  s.window = {256, 1200 + 128};
  const RenderedFrame f = renderer.render(s);
  for (int r = 0; r < d.y; ++r)
    for (int c = 0; c < d.x; ++c) {
      const double expected = (1200 + 3 * r + c) - 1200.0;  // grey = value - (level - window/2)
      ASSERT_NEAR(f.image.pixel(c, r)[0], expected, 1.0) << c << "," << r;
    }
  // A 10 mm slab MIP around z = 24 mm: midpoint samples every 0.5 mm, the deepest at
  // z = 28.75 mm = slice 14.375, where the (linear in z) value is 1437.5 + 3 j + i.
  s.slabMm = 10.0;
  s.window.level = 1400 + 128;
  const RenderedFrame slab = renderer.render(s);
  EXPECT_NEAR(slab.image.pixel(5, 7)[0], (1437.5 + 21 + 5) - 1400.0, 1.0);
}

TEST(Mpr, FunctionalOverlayFollowsTheRegistrationTransform) {
  const Volume anatomy = makeVolume({41, 41, 21}, test::axisGrid({-20, -20, -10}, {1, 1, 1}),
                                    [](glm::dvec3) { return 0.0f; });
  // A hot 8 mm cube at the functional origin, on a coarse 4 mm grid.
  const Volume hot =
      makeVolume({11, 11, 11}, test::axisGrid({-20, -20, -20}, {4, 4, 4}), [](glm::dvec3 p) {
        return glm::all(glm::lessThan(glm::abs(p), glm::dvec3(4.1))) ? 10.0f : 0.0f;
      });
  test::Renderer renderer(anatomy);
  RenderSettings s =
      test::settingsOf({.mode = RenderMode::Mpr, .size = {41, 41}, .view = StandardView::Inferior});
  s.camera.zoom = framingSphere(anatomy).radius / 20.5;
  s.window = {100, 50};
  s.overlay.opacity = 1.0f;
  s.overlay.threshold = 0.5f;
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
