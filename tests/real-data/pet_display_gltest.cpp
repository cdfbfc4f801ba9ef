// The real whole-body FDG PET (../shared/data/pet-fdg-wholebody) displayed as a reader reads it:
// an axial MIP at one pixel per voxel, nearest sampling, equals the CPU maximum of the SUVbw
// values along S mapped through the window (0..8) and the colour map, for inverted grey and
// Hot Iron, every pixel; the anterior inverted MIP shows its empty background white and its
// hottest pixel black.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "../render/RenderTestUtil.h"
#include "SharedData.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace {

using namespace mvw;

TEST(RealPetDisplay, AxialMipIsTheCpuMaximumThroughTheColourMap) {
  MVW_REQUIRE_SHARED_DATA("pet-fdg-wholebody");
  io::ReadOptions options;
  options.series = "PET WB";
  const Volume pet = io::readVolume(sharedPath, options);
  ASSERT_EQ(pet.metadata().unit, "SUVbw");
  const glm::ivec3 d = pet.dimensions();
  ASSERT_EQ(d, glm::ivec3(128, 128, 299));
  ASSERT_NEAR(pet.spacing().x, pet.spacing().y, 1e-6);  // square pixels in the axial plane

  // The CPU maximum along k (S) per (i, j), as the window maps it: grey = round(255 SUV / 8).
  std::vector<int> expected(static_cast<std::size_t>(d.x * d.y));
  for (int j = 0; j < d.y; ++j)
    for (int i = 0; i < d.x; ++i) {
      double m = -1e30;
      for (int k = 0; k < d.z; ++k) m = std::max(m, pet.value(i, j, k));
      expected[static_cast<std::size_t>(j * d.x + i)] =
          static_cast<int>(std::lround(255.0 * std::clamp(m / 8.0, 0.0, 1.0)));
    }

  test::Renderer renderer(pet);
  // From the feet: screen right = +x (index i), screen down = +y (index j), one pixel a voxel.
  render::RenderSettings s = test::settingsOf({.mode = RenderMode::Mip,
                                               .size = {d.x, d.y},
                                               .view = render::StandardView::Inferior,
                                               .jitterOff = true});
  s.camera.zoom = render::framingSphere(pet).radius / (0.5 * d.y * pet.spacing().y);
  s.linear = false;  // nearest: the samples are the voxels' own values
  s.window = {8.0, 4.0};
  for (ColorMap map : {ColorMap::GreyInverted, ColorMap::HotIron}) {
    s.imageColors = io::standardColorTable(map);
    const Image img = renderer.render(s).image;
    int off = 0, worst = 0;
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const auto& want =
            s.imageColors
                ->rgb[static_cast<std::size_t>(expected[static_cast<std::size_t>(j * d.x + i)])];
        for (int c = 0; c < 3; ++c) {
          const int delta =
              std::abs(int(img.pixel(i, j)[c]) - int(want[static_cast<std::size_t>(c)]));
          worst = std::max(worst, delta);
          off += delta > 0 ? 1 : 0;
        }
      }
    // Every channel of every pixel exact (measured: 0 values off of 3 x 128 x 128).
    EXPECT_EQ(worst, 0) << toString(map);
    EXPECT_EQ(off, 0) << toString(map);
  }
}

TEST(RealPetDisplay, InvertedAnteriorMipHasAWhiteBackgroundAndABlackHottestSpot) {
  MVW_REQUIRE_SHARED_DATA("pet-fdg-wholebody");
  io::ReadOptions options;
  options.series = "PET WB";
  const Volume pet = io::readVolume(sharedPath, options);
  test::Renderer renderer(pet);
  render::RenderSettings s = test::settingsOf(
      {.mode = RenderMode::Mip, .size = {101, 201}, .view = render::StandardView::Anterior});
  s.window = {8.0, 4.0};
  s.imageColors = io::standardColorTable(ColorMap::GreyInverted);
  const Image img = renderer.render(s).image;
  EXPECT_EQ(img.pixel(0, 0)[0], 255);  // outside the box: the background, white
  int darkest = 255;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) darkest = std::min<int>(darkest, img.pixel(x, y)[0]);
  EXPECT_EQ(darkest, 0);  // SUVmax 19.5 saturates the 0..8 window: black
}

}  // namespace
