// Colour maps on the image of MIP (also depth-cued), MinIP, average and MPR views, and on the
// functional overlay: every pixel is the palette's entry at the grey byte the grey render shows,
// the hottest pixel of a sphere's MIP is the palette's top colour, and grey-inverted shows the
// empty background white.
#include <cmath>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

// A bright ball (value 1000 at the centre falling to 0 at 12 mm) in a 41 mm box of zeros.
Volume sphere() {
  return makeVolume({41, 41, 41}, test::axisGrid({-20, -20, -20}, {1, 1, 1}), [](glm::dvec3 p) {
    return static_cast<float>(std::max(0.0, 1000.0 * (1.0 - glm::length(p) / 12.0)));
  });
}

RenderSettings mipOf(RenderMode mode) {
  RenderSettings s = test::settingsOf({.mode = mode, .size = {61, 61}, .jitterOff = true});
  s.window = {1000, 500};
  return s;
}

// Every pixel of `coloured` is table[grey byte of the same pixel of `grey`].
void expectMapped(const Image& grey, const Image& coloured, const ColorTable& table) {
  ASSERT_EQ(grey.width, coloured.width);
  int checked = 0;
  for (int y = 0; y < grey.height; ++y)
    for (int x = 0; x < grey.width; ++x) {
      const auto g = static_cast<std::size_t>(grey.pixel(x, y)[0]);
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(coloured.pixel(x, y)[c], table.rgb[g][static_cast<std::size_t>(c)])
            << toString(table.map) << " at " << x << "," << y << " grey " << g << " channel " << c;
      ++checked;
    }
  EXPECT_EQ(checked, grey.width * grey.height);
}

const ColorMap kMaps[] = {ColorMap::GreyInverted, ColorMap::HotIron, ColorMap::Pet,
                          ColorMap::HotMetalBlue, ColorMap::Pet20Step};

TEST(ColorMaps, MipPixelsAreThePalettesEntryAtTheGreyLevel) {
  const Volume v = sphere();
  test::Renderer renderer(v);
  for (RenderMode mode :
       {RenderMode::Mip, RenderMode::MinIp, RenderMode::Average, RenderMode::Mpr}) {
    RenderSettings s = mipOf(mode);
    const Image grey = renderer.render(s).image;
    for (ColorMap map : kMaps) {
      s.imageColors = io::standardColorTable(map);
      SCOPED_TRACE(toString(mode));
      expectMapped(grey, renderer.render(s).image, *s.imageColors);
    }
  }
}

TEST(ColorMaps, HottestPixelOfASphereMipIsThePalettesTopColour) {
  const Volume v = sphere();
  test::Renderer renderer(v);
  RenderSettings s = mipOf(RenderMode::Mip);
  s.window = {980, 490};  // the centre (1000 at the ray through it) saturates: grey 255
  const Image grey = renderer.render(s).image;
  ASSERT_EQ(grey.pixel(30, 30)[0], 255);
  for (ColorMap map : kMaps) {
    s.imageColors = io::standardColorTable(map);
    const Image img = renderer.render(s).image;
    const auto& top = s.imageColors->rgb[255];
    for (int c = 0; c < 3; ++c) EXPECT_EQ(img.pixel(30, 30)[c], top[static_cast<std::size_t>(c)]);
    // The corner sees only zeros (inside the box) : the palette's lowest colour.
    const auto& bottom = s.imageColors->rgb[0];
    for (int c = 0; c < 3; ++c) EXPECT_EQ(img.pixel(1, 1)[c], bottom[static_cast<std::size_t>(c)]);
  }
}

TEST(ColorMaps, GreyInvertedShowsAWhiteBackgroundAndBlackHotSpot) {
  const Volume v = sphere();
  test::Renderer renderer(v);
  RenderSettings s = mipOf(RenderMode::Mip);
  s.window = {980, 490};
  s.camera.zoom = 0.5;  // rays that miss the box: the background
  s.imageColors = io::standardColorTable(ColorMap::GreyInverted);
  const Image img = renderer.render(s).image;
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(img.pixel(0, 0)[c], 255) << "background";
    EXPECT_EQ(img.pixel(30, 30)[c], 0) << "hottest";
  }
  // Depth-cued MIP keeps the background term of eq. (3) on the black (emission) background.
  s.depthCue.on = true;
  s.depthCue.amount = 0.5;
  s.depthCue.contrast = 0.5;
  const Image cued = renderer.render(s).image;
  EXPECT_EQ(cued.pixel(0, 0)[0], 255);
  RenderSettings greyCue = s;
  greyCue.imageColors.reset();
  expectMapped(renderer.render(greyCue).image, cued, *s.imageColors);
}

TEST(ColorMaps, OverlayUsesItsOwnColourMap) {
  const glm::dmat4 grid = test::axisGrid({-20, -20, -10}, {1, 1, 1});
  const Volume anatomy = makeVolume({41, 41, 21}, grid, [](glm::dvec3) { return 0.0f; });
  // A uniform attribute of 7 in the window 0 .. 10: u = 0.7 everywhere, palette entry
  // floor(0.7 * 256) = 179 (the overlay's table is sampled nearest).
  const Volume uptake = makeVolume({41, 41, 21}, grid, [](glm::dvec3) { return 7.0f; });
  test::Renderer renderer(anatomy);
  renderer.setFunctional(uptake, glm::dmat4(1.0));
  RenderSettings s = mipOf(RenderMode::Mpr);
  s.camera.view = StandardView::Inferior;
  s.functionalWindow = {0.0, 10.0};
  s.overlay.opacity = 1.0f;
  s.overlay.threshold = 0.0f;
  for (ColorMap map : {ColorMap::HotIron, ColorMap::Pet, ColorMap::HotMetalBlue,
                       ColorMap::Pet20Step, ColorMap::GreyInverted}) {
    s.overlayColors = io::standardColorTable(map);
    const Image img = renderer.render(s).image;
    const auto& want = s.overlayColors->rgb[179];
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(img.pixel(30, 30)[c], want[static_cast<std::size_t>(c)]) << toString(map);
  }
  // The default stays the hot metal preset's (interpolated) colour.
  s.overlayColors.reset();
  const Image def = renderer.render(s).image;
  const auto hot = sampleTransferFunction(transferPreset("pet-hot-metal"), 0, 1, 256, 0, 1);
  EXPECT_NEAR(def.pixel(30, 30)[0], 255 * hot[179].r, 2.0);
  EXPECT_NEAR(def.pixel(30, 30)[1], 255 * hot[179].g, 2.0);
  EXPECT_NEAR(def.pixel(30, 30)[2], 255 * hot[179].b, 2.0);
}

}  // namespace
}  // namespace mvw::render
