// The render target is kept between frames and recreated only when the size changes: frames of
// changing sizes must equal those of a renderer that has drawn nothing else.
#include <vector>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

TEST(RenderTarget, FramesOfChangingSizesEqualThoseOfAFreshRenderer) {
  const Volume v =
      makeVolume({30, 20, 10}, test::axisGrid({0, 0, 0}, {1, 1.5, 2}),
                 [](glm::dvec3 p) { return static_cast<float>(p.x * 10 + p.y * 3 + p.z); });
  RenderSettings s;
  s.transfer = transferPreset("mr-default");
  s.camera.azimuthDeg = 30;
  // Odd sizes, and a mode that reports depth (-1 where a ray misses) next to one that does not.
  const std::vector<std::pair<glm::ivec2, RenderMode>> frames = {
      {{47, 31}, RenderMode::Composite}, {{47, 31}, RenderMode::Mip},
      {{19, 53}, RenderMode::Composite}, {{47, 31}, RenderMode::Isosurface},
      {{1, 1}, RenderMode::Mpr},         {{19, 53}, RenderMode::Mip}};
  test::Renderer reused(v);
  for (const auto& [size, mode] : frames) {
    s.size = size;
    s.mode = mode;
    s.iso = 150;
    const RenderedFrame a = reused.render(s);
    VolumeRenderer fresh(reused.context(), v);
    const RenderedFrame b = fresh.render(s);
    ASSERT_EQ(a.image.width, size.x);
    ASSERT_EQ(a.image.height, size.y);
    EXPECT_EQ(a.image.rgba, b.image.rgba) << toString(mode) << " " << size.x << " x " << size.y;
    EXPECT_EQ(a.image.depth, b.image.depth) << toString(mode) << " " << size.x << " x " << size.y;
  }
}

}  // namespace
}  // namespace mvw::render
