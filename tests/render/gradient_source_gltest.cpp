// Where shading takes the gradient from (GradientSource): the precomputed texture (float, or
// packed with 16-bit intensities) and the shaders' central differences all light a sphere as
// Lambert says, composite reads the same values from the packed texture as from the intensity,
// glyphs work on each from their first frame, and voxels of every integer type reach the
// shaders with their values at the type's ends.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

// Value = R - distance to the centre: the 0-isosurface is a sphere of radius R around 0.
Volume sphere(double R, glm::ivec3 dims, glm::dvec3 origin, glm::dvec3 spacing) {
  return makeVolume(dims, test::axisGrid(origin, spacing),
                    [R](glm::dvec3 p) { return static_cast<float>(R - glm::length(p)); });
}

// The same in int16 hundredths of a mm: 16-bit intensities, so the gradient texture is packed
// with them (RGBA16) instead of float (RGBA16F).
Volume sphere16(double R, glm::ivec3 dims, glm::dvec3 origin, glm::dvec3 spacing) {
  return test::makeVolumeOf<std::int16_t>(dims, test::axisGrid(origin, spacing), [R](glm::dvec3 p) {
    return std::lround(100.0 * (R - glm::length(p)));
  });
}

struct Source {
  const char* name;
  bool int16;
  GradientSource gradient;
};
const Source kSources[] = {{"float texture", false, GradientSource::Texture},
                           {"packed texture (int16)", true, GradientSource::Texture},
                           {"shader (float)", false, GradientSource::OnTheFly},
                           {"shader (int16)", true, GradientSource::OnTheFly}};

// The worst |pixel - Lambert| (grey levels) over the rays that hit the sphere well inside its
// outline, for an isosurface lit by a headlight with ambient 0.2 and diffuse 0.8.
double worstLambertError(VolumeRenderer& renderer, double R, const glm::dvec3& centre) {
  RenderSettings s =
      test::settingsOf({.mode = RenderMode::Isosurface, .size = {65, 65}, .jitterOff = true});
  s.iso = 0.0;
  s.camera.zoom = 2.5;
  s.camera.azimuthDeg = 20;
  s.camera.elevationDeg = 15;
  s.isoColor = {1.0f, 1.0f, 1.0f, 1.0f};
  s.light = {0.2f, 0.8f, 0.0f, 1.0f};
  const RenderedFrame f = renderer.render(s);
  double worst = 0.0;
  int checked = 0;
  for (int r = 0; r < s.size.y; ++r)
    for (int c = 0; c < s.size.x; ++c) {
      const glm::dvec2 ndc((c + 0.5) / s.size.x * 2 - 1, 1 - (r + 0.5) / s.size.y * 2);
      const WorldRay ray = rayThrough(f.camera, ndc);
      const double along = glm::dot(centre - ray.origin, ray.direction);
      const double rho2 = glm::dot(centre - ray.origin, centre - ray.origin) - along * along;
      if (rho2 > (0.85 * R) * (0.85 * R)) continue;
      const glm::dvec3 hit = ray.origin + (along - std::sqrt(R * R - rho2)) * ray.direction;
      const double cosine = glm::dot(glm::normalize(hit - centre), -ray.direction);
      const double expected = 255.0 * (0.2 + 0.8 * cosine);
      worst = std::max(worst, std::abs(f.image.pixel(c, r)[0] - expected));
      ++checked;
    }
  EXPECT_GT(checked, 1000);
  return worst;
}

TEST(GradientSource, EverySourceLightsASphereAsLambertSays) {
  const double R = 20.0;
  const Volume v = sphere(R, {65, 65, 33}, {-32, -32, -24}, {1.0, 1.0, 1.5});
  const Volume v16 = sphere16(R, {65, 65, 33}, {-32, -32, -24}, {1.0, 1.0, 1.5});
  auto ctx = test::headlessContext();
  for (const Source& source : kSources) {
    VolumeRenderer renderer(*ctx, source.int16 ? v16 : v, source.gradient);
    EXPECT_EQ(renderer.gradientSource(), source.gradient);
    const double worst = worstLambertError(renderer, R, glm::dvec3(0.0));
    std::cout << "gradient from the " << source.name << ": worst Lambert error " << worst
              << " grey levels\n";
    // Measured: 1.9 (texture) and 1.8 (shader) grey levels, the normal within about half a
    // degree, for float and int16 alike. A gradient axis scaled by the wrong spacing, a flipped
    // axis or a wrong packed decoding costs tens of levels.
    EXPECT_LT(worst, 3.0) << source.name;
  }
}

// The same sphere on a sheared grid (the slice axis tilted 25 degrees toward +y, as a
// gantry-tilted CT kept in its matrix): positions follow the matrix, and so must the normals.
// Taking the direction cosines as if the axes were perpendicular tilts every normal.
TEST(GradientSource, AShearedGridLightsTheSphereAsLambertSays) {
  const double R = 20.0, tilt = 25.0 * 3.14159265358979323846 / 180.0;
  glm::dmat4 w(1.0);
  w[1] = glm::dvec4(0.0, 1.0, 0.0, 0.0);
  w[2] = glm::dvec4(0.0, 1.2 * std::sin(tilt), 1.2 * std::cos(tilt), 0.0);
  w[3] = glm::dvec4(glm::dvec3(-32.0, -32.0, 0.0) - 20.0 * glm::dvec3(w[2]), 1.0);
  const Volume v = makeVolume({65, 65, 41}, w,
                              [R](glm::dvec3 p) { return static_cast<float>(R - glm::length(p)); });
  auto ctx = test::headlessContext();
  for (GradientSource gradient : {GradientSource::Texture, GradientSource::OnTheFly}) {
    VolumeRenderer renderer(*ctx, v, gradient);
    const double worst = worstLambertError(renderer, R, glm::dvec3(0.0));
    std::cout << "sheared grid, gradient from the " << toString(gradient)
              << ": worst Lambert error " << worst << " grey levels\n";
    EXPECT_LT(worst, 3.0) << toString(gradient);
  }
}

// Shaded composite of the int16 sphere: with the packed texture its samples take value and
// gradient from one fetch (the intensity's texel in A); on the fly, from the R16 intensity.
// The same values and nearly the same normals must give the same image.
TEST(GradientSource, PackedCompositeSeesTheIntensitysValues) {
  const Volume v16 = sphere16(20.0, {65, 65, 33}, {-32, -32, -24}, {1.0, 1.0, 1.5});
  auto ctx = test::headlessContext();
  RenderSettings s =
      test::settingsOf({.mode = RenderMode::Composite, .size = {97, 97}, .jitterOff = true});
  // Values in hundredths of a mm: a 2 mm translucent rind over an opaque core.
  s.transfer = TransferFunction{
      "rind",
      false,
      {TfPoint{-100.0, {1, 0.8f, 0.6f, 0.0f}}, TfPoint{100.0, {1, 0.8f, 0.6f, 0.05f}},
       TfPoint{400.0, {0.6f, 0.7f, 1, 0.05f}}, TfPoint{500.0, {0.6f, 0.7f, 1, 1.0f}}}};
  s.camera.azimuthDeg = 20;
  s.camera.elevationDeg = 15;
  const Image packed = VolumeRenderer(*ctx, v16, GradientSource::Texture).render(s).image;
  const Image shader = VolumeRenderer(*ctx, v16, GradientSource::OnTheFly).render(s).image;
  int worst = 0, lit = 0;
  for (std::size_t i = 0; i < packed.rgba.size(); ++i) {
    worst = std::max(worst, std::abs(int(packed.rgba[i]) - int(shader.rgba[i])));
    if (i % 4 == 0 && packed.rgba[i] > 60) ++lit;
  }
  std::cout << "packed against on the fly: worst " << worst << " grey levels, " << lit
            << " lit pixels\n";
  EXPECT_GT(lit, 500);
  // The two gradients differ (Sobel-averaged against plain central differences): a few levels.
  // A value read from the wrong channel or mapped wrongly moves the rind by tens.
  EXPECT_LE(worst, 8);
}

TEST(GradientSource, AutoKeepsTheTextureForSmallVolumesAndNamesTheChoices) {
  const Volume v = sphere(10.0, {24, 24, 24}, {-12, -12, -12}, {1, 1, 1});
  auto ctx = test::headlessContext();
  EXPECT_EQ(VolumeRenderer(*ctx, v).gradientSource(), GradientSource::Texture);
  EXPECT_EQ(parseGradientSource("shader"), GradientSource::OnTheFly);
  EXPECT_EQ(parseGradientSource("texture"), GradientSource::Texture);
  EXPECT_EQ(parseGradientSource("auto"), GradientSource::Auto);
  EXPECT_THROW(parseGradientSource("sobel"), Error);
}

// Glyphs, with their attribute in the float gradient's A or in a volume of its own (packed,
// on the fly): no attribute is plain shading bit for bit, and glyphs appear only where the
// attribute is, from the renderer's first glyph frame on (the attribute volume, made by that
// frame, once took the functional volume's texture unit, and that frame had no attribute).
TEST(GradientSource, GlyphsWorkWithEverySourceFromTheFirstFrame) {
  const Volume anatomy = sphere(25.0, {61, 61, 61}, {-30, -30, -30}, {1, 1, 1});
  const Volume anatomy16 = sphere16(25.0, {61, 61, 61}, {-30, -30, -30}, {1, 1, 1});
  auto attribute = [](float level) {
    return makeVolume({16, 16, 16}, test::axisGrid({-30, -30, -30}, {4, 4, 4}),
                      [level](glm::dvec3 p) { return p.x > 2.0 ? level : 0.0f; });
  };
  auto ctx = test::headlessContext();
  for (const Source& source : kSources)
    for (RenderMode mode : {RenderMode::Isosurface, RenderMode::Composite}) {
      const Volume& volume = source.int16 ? anatomy16 : anatomy;
      const double unit = source.int16 ? 100.0 : 1.0;
      const std::string what = std::string(source.name) + ", " + toString(mode);
      RenderSettings s = test::settingsOf(
          {.mode = mode, .size = {241, 241}, .view = StandardView::Anterior, .jitterOff = true});
      s.iso = 0.0;
      s.transfer =
          TransferFunction{"shell",
                           false,
                           {TfPoint{-1.0 * unit, {1, 1, 1, 0.0f}}, TfPoint{0.0, {1, 1, 1, 1.0f}},
                            TfPoint{30.0 * unit, {1, 1, 1, 1.0f}}}};
      s.glyphDiameterMm = 4.0;
      s.functionalWindow = {0.0, 1.0};
      VolumeRenderer renderer(*ctx, volume, source.gradient);
      const RenderedFrame plain = renderer.render(s);
      s.glyphs.on = true;
      VolumeRenderer first(*ctx, volume, source.gradient);
      first.setFunctional(attribute(0.8f), glm::dmat4(1.0));
      const Image bumped = first.render(s).image;
      int changed = 0, wrongSide = 0;
      for (int y = 0; y < bumped.height; ++y)
        for (int x = 0; x < bumped.width; ++x)
          if (std::memcmp(bumped.pixel(x, y), plain.image.pixel(x, y), 3) != 0) {
            ++changed;
            if (x < bumped.width / 2 - 1) ++wrongSide;
          }
      std::cout << what << ": " << changed << " pixels changed by glyphs\n";
      EXPECT_GT(changed, 150) << what;
      EXPECT_EQ(wrongSide, 0) << what;
      renderer.setFunctional(attribute(0.0f), glm::dmat4(1.0));
      EXPECT_EQ(renderer.render(s).image.rgba, plain.image.rgba) << what;
    }
}

// Three slabs at the type's lowest value, its middle and its highest, seen by a MIP through
// each slab alone with nearest sampling, the window spanning the type: black, mid grey,
// white. A wrong value mapping (a signed type's offset, a normalised texel's scale) moves them.
template <class T>
void expectTypeEndsReachTheShader(double lo, double mid, double hi) {
  const glm::ivec3 dims(24, 24, 24);
  // On a 1 mm grid from 0, x is the voxel's index i.
  const Volume v =
      test::makeVolumeOf<T>(dims, test::axisGrid({0, 0, 0}, {1, 1, 1}), [&](glm::dvec3 p) {
        return p.x < 8 ? lo : p.x < 16 ? mid : hi;
      });
  test::Renderer renderer(v);
  EXPECT_EQ(renderer.valueRange(), (std::pair{lo, hi}));
  RenderSettings s = test::settingsOf({
      .mode = RenderMode::Mip,
      .size = {48, 48},
      .view = StandardView::Anterior,  // rays along +y: each pixel column sees one i
      .jitterOff = true,
  });
  s.linear = false;
  s.window = {hi - lo, (hi + lo) / 2};
  const Image image = renderer.render(s).image;
  // Screen right is patient left (+x, high i); columns well inside each slab.
  const double expected[3] = {0.0, 255.0 * (mid - lo) / (hi - lo), 255.0};
  // 48 pixels over the framing sphere's 41.6 mm: slab centres at about columns 15, 24, 33.
  const int columns[3] = {15, 24, 33};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(image.pixel(columns[c], 24)[0], expected[c], 1.0)
        << scalarName(scalarTypeOf<T>()) << ", slab " << c;
}

TEST(GradientSource, EveryScalarTypeReachesTheShaderAtItsEnds) {
  expectTypeEndsReachTheShader<std::uint8_t>(0, 100, 255);
  expectTypeEndsReachTheShader<std::int8_t>(-128, 0, 127);
  expectTypeEndsReachTheShader<std::uint16_t>(0, 30000, 65535);
  expectTypeEndsReachTheShader<std::int16_t>(-32768, -1024, 32767);
  expectTypeEndsReachTheShader<float>(-1000.5, 3.25, 2500.75);
}

}  // namespace
}  // namespace mvw::render
