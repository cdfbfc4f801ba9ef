// Left and right must be right: markers toward L, P and S land where the orientation labels
// say, whatever order the voxels are stored in.

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::Centroid;
using test::centroidOf;
using test::makeVolume;

// A dark cube with bright markers 15 mm toward the patient's left, posterior and superior.
float markers(glm::dvec3 p) {
  auto near = [&](glm::dvec3 c) { return glm::length(p - c) < 4.0; };
  if (near({15, 0, 0})) return 1000.0f;  // L
  if (near({0, 15, 0})) return 600.0f;   // P
  if (near({0, 0, 15})) return 300.0f;   // S
  return 0.0f;
}

TEST(Raycast, MarkersAppearWhereTheOrientationLabelsSayForAnyStorageOrder) {
  // The same world content stored in LPS order and in RAS order (flipped i and j).
  const glm::ivec3 d(41, 41, 41);
  const Volume lps =
      makeVolume(d, makeWorldFromIndex({-20, -20, -20}, {1, 1, 1}, glm::dmat3(1.0)), markers);
  const Volume ras =
      makeVolume(d,
                 makeWorldFromIndex(
                     {20, 20, -20}, {1, 1, 1},
                     glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1))),
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
    EXPECT_GT(left.x, 65);  // L marker on the right half
    EXPECT_NEAR(left.y, 50, 3);
    EXPECT_LT(sup.y, 35);  // S marker at the top
    EXPECT_NEAR(sup.x, 50, 3);
    s.camera.view = StandardView::Left;  // screen right = posterior
    f = renderer.render(s);
    const Centroid post = centroidOf(f.image, 148, 158);
    ASSERT_GT(post.n, 10);
    EXPECT_GT(post.x, 65);
    EXPECT_NEAR(post.y, 50, 3);
  }
}

}  // namespace
}  // namespace mvw::render
