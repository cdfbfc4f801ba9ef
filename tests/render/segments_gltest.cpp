// Segment outlines on MPR: a segment's edge pixels take its colour, its inside and the outside
// keep the image, the segmentation is placed by its own transform, the lowest-numbered segment
// wins where two edges meet, and switching outlines off leaves the image untouched.
#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

TEST(SegmentOutlines, EdgesInTheSegmentColoursWherePlaced) {
  const Volume anatomy = makeVolume({41, 41, 21}, test::axisGrid({-20, -20, -10}, {1, 1, 1}),
                                    [](glm::dvec3) { return 0.0f; });
  // Two segments on a 1 mm grid of their own: 1 = |x| <= 5, |y| <= 5; 2 = |x - 3| <= 2,
  // |y| <= 2 (inside 1, sharing its right edge), every slice.
  Volume masks({41, 41, 21}, 2, ScalarType::UInt8, test::axisGrid({-20, -20, -10}, {1, 1, 1}));
  for (int k = 0; k < 21; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 41; ++i) {
        const int x = i - 20, y = j - 20;
        masks.setValue(i, j, k, 0, std::abs(x) <= 5 && std::abs(y) <= 5);
        masks.setValue(i, j, k, 1, std::abs(x - 3) <= 2 && std::abs(y) <= 2);
      }
  test::Renderer renderer(anatomy);
  // Placed 5 mm toward the patient's left (+x): segment 1 spans x 0 .. 10 on the anatomy.
  glm::dmat4 shift(1.0);
  shift[3] = glm::dvec4(5, 0, 0, 1);
  renderer.setSegmentation(masks, {{1.0f, 0.6f, 0.0f}, {0.0f, 1.0f, 1.0f}}, shift);
  RenderSettings s = test::settingsOf({
      .mode = RenderMode::Mpr,
      .size = {41, 41},
      .view = StandardView::Inferior,  // screen right = +x, down = +y, 1 pixel per mm
  });
  s.camera.zoom = framingSphere(anatomy).radius / 20.5;
  s.window = {100, 50};
  const Image img = renderer.render(s).image;
  auto rgb = [&](int x, int y) {
    const std::uint8_t* p = img.pixel(x + 20, y + 20);
    return glm::ivec3(p[0], p[1], p[2]);
  };
  const glm::ivec3 orange(255, 153, 0), cyan(0, 255, 255), black(0);
  EXPECT_EQ(rgb(0, 0), orange);   // left edge of segment 1
  EXPECT_EQ(rgb(0, -5), orange);  // corner
  EXPECT_EQ(rgb(5, 5), orange);   // bottom edge
  EXPECT_EQ(rgb(5, -5), orange);  // top edge
  EXPECT_EQ(rgb(10, 0), orange);  // right edge, shared with segment 2: the lower number wins
  EXPECT_EQ(rgb(6, 0), cyan);     // segment 2's left edge, inside segment 1
  EXPECT_EQ(rgb(8, 2), cyan);     // segment 2's bottom edge
  EXPECT_EQ(rgb(2, 0), black);    // inside segment 1 only
  EXPECT_EQ(rgb(8, 0), black);    // inside segment 2
  EXPECT_EQ(rgb(-1, 0), black);   // outside, next to the edge
  EXPECT_EQ(rgb(11, 0), black);
  int coloured = 0;
  for (int y = -20; y <= 20; ++y)
    for (int x = -20; x <= 20; ++x) coloured += rgb(x, y) != black;
  // Segment 1's outline: 11 x 11 square ring (40 pixels); segment 2's: 5 x 5 ring (16) less
  // its 5 pixels on segment 1's right edge.
  EXPECT_EQ(coloured, 40 + 16 - 5);

  s.segmentationOutlines = false;
  const Image off = renderer.render(s).image;
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 41; ++x) ASSERT_EQ(off.pixel(x, y)[0], 0) << x << "," << y;
}

}  // namespace
}  // namespace mvw::render
