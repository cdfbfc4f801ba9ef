// The ray caster runs only where the crop box's proxy falls (BoxProxy.h); the rest of the
// target is cleared. Checked against rays traced on the CPU: every pixel whose ray crosses the
// box is drawn, every other pixel shows exactly the background a ray that meets nothing
// writes, with no depth, for orthographic and perspective cameras, oblique volumes and crops.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

// The chord (mm) of a ray through the index box [lo, hi] enlarged by `grow` voxels, or nullopt
// where it misses.
std::optional<double> chordThroughBox(const Volume& v, const WorldRay& ray, glm::dvec3 lo,
                                      glm::dvec3 hi, double grow) {
  const auto span = test::rayThroughIndexBox(v, ray, lo, hi, grow);
  if (!span) return std::nullopt;
  return span->second - span->first;
}

struct Case {
  std::string name;
  glm::dmat3 direction{1.0};
  CameraSettings camera;
  glm::dvec3 cropMin{0.0}, cropMax{1.0};
  bool fillsView = false;  // every ray crosses the box
};

glm::dmat3 rotation(double zDeg, double xDeg) {
  const double a = glm::radians(zDeg), b = glm::radians(xDeg);
  const glm::dmat3 rz(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);
  const glm::dmat3 rx(1, 0, 0, 0, std::cos(b), std::sin(b), 0, -std::sin(b), std::cos(b));
  return rz * rx;
}

TEST(Raycast, OnlyPixelsWhoseRayMissesTheBoxAreLeftToTheClearedBackground) {
  CameraSettings oblique;
  oblique.azimuthDeg = 37.0;
  oblique.elevationDeg = 23.0;
  oblique.rollDeg = 11.0;
  CameraSettings perspective = oblique;
  perspective.perspective = true;
  perspective.azimuthDeg = -30.0;
  CameraSettings close = perspective;
  close.zoom = 4.0;
  close.panMm = {9.0, -5.0};
  CameraSettings inside = perspective;  // the eye just outside the framing sphere: corners of
  inside.zoom = 2000.0;                 // the enlarged box lie behind its plane
  CameraSettings edgeOn;                // the side faces seen exactly edge-on
  CameraSettings superior;
  superior.view = StandardView::Superior;
  superior.azimuthDeg = 90.0;
  const Case cases[] = {
      {"anterior", glm::dmat3(1.0), edgeOn},
      {"oblique camera", glm::dmat3(1.0), oblique},
      {"perspective", glm::dmat3(1.0), perspective},
      {"perspective, close", glm::dmat3(1.0), close},
      {"oblique volume", rotation(30.0, 20.0), oblique},
      {"oblique volume, perspective", rotation(-50.0, 35.0), perspective},
      {"cropped", glm::dmat3(1.0), oblique, {0.2, 0.1, 0.3}, {0.7, 0.9, 0.6}},
      {"cropped, superior", glm::dmat3(1.0), superior, {0.25, 0.0, 0.1}, {0.8, 0.5, 0.9}},
      {"perspective, eye at the box", glm::dmat3(1.0), inside, glm::dvec3(0.0), glm::dvec3(1.0),
       true},
  };
  const glm::ivec3 dims(40, 32, 24);
  const glm::vec3 background(0.3f, 0.5f, 0.7f);
  auto ctx = test::headlessContext();
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    // Constant above the isovalue: a ray that enters the (cropped) box hits its face there.
    const Volume v =
        makeVolume(dims, makeWorldFromIndex({-20.0, -12.0, -18.0}, {1.0, 1.25, 1.5}, c.direction),
                   [](glm::dvec3) { return 100.0f; });
    VolumeRenderer renderer(*ctx, v);
    RenderSettings s =
        test::settingsOf({.mode = RenderMode::Isosurface, .size = {160, 128}, .jitterOff = true});
    s.iso = 50.0;
    s.camera = c.camera;
    s.crop.min = c.cropMin;
    s.crop.max = c.cropMax;
    s.background = background;
    s.stepMm = 0.25;
    const RenderedFrame f = renderer.render(s);
    const glm::dvec3 lo = c.cropMin * glm::dvec3(dims) - 0.5;
    const glm::dvec3 hi = c.cropMax * glm::dvec3(dims) - 0.5;
    const auto at = [&](int x, int y) { return f.image.pixel(x, y); };
    // The background as the shader writes it: the top-left pixel, whose ray misses.
    const glm::dvec2 cornerNdc(-1.0 + 1.0 / s.size.x, 1.0 - 1.0 / s.size.y);
    if (!c.fillsView) {
      ASSERT_FALSE(chordThroughBox(v, rayThrough(f.camera, cornerNdc), lo, hi, 0.0));
    }
    int drawn = 0, missed = 0, wrong = 0;
    for (int y = 0; y < s.size.y; ++y)
      for (int x = 0; x < s.size.x; ++x) {
        const glm::dvec2 ndc((x + 0.5) / s.size.x * 2 - 1, 1 - (y + 0.5) / s.size.y * 2);
        const WorldRay ray = rayThrough(f.camera, ndc);
        const double depth = f.image.depth[static_cast<std::size_t>(y) * s.size.x + x];
        const auto* p = at(x, y);
        const bool isBackground =
            p[0] == at(0, 0)[0] && p[1] == at(0, 0)[1] && p[2] == at(0, 0)[2] && depth == -1.0;
        if (const auto chord = chordThroughBox(v, ray, lo, hi, 1e-3)) {
          if (*chord < 4.0 * s.stepMm) continue;  // grazing: may take no sample
          ++drawn;
          if (isBackground || depth < 0.0) ++wrong;
        } else {
          ++missed;
          if (!isBackground) ++wrong;
        }
      }
    std::cout << c.name << ": " << drawn << " pixels whose ray crosses the box, " << missed
              << " whose ray misses it, " << wrong << " wrong\n";
    EXPECT_GT(drawn, 500);
    if (!c.fillsView) {
      EXPECT_GT(missed, 500);
    }
    EXPECT_EQ(wrong, 0);
  }
}

// The samples `mvw bench render` puts against the ceiling (VolumeRenderer::nominalSamples): each
// ray's chord through the crop box over the step, summed over the image, as the rays traced on
// the CPU give them, for orthographic and perspective cameras, an oblique volume and a crop.
TEST(Raycast, NominalSamplesAreEveryRaysChordThroughTheBoxOverTheStep) {
  CameraSettings oblique;
  oblique.azimuthDeg = 37.0;
  oblique.elevationDeg = 23.0;
  CameraSettings perspective = oblique;
  perspective.perspective = true;
  perspective.zoom = 1.7;
  const Case cases[] = {
      {"anterior", glm::dmat3(1.0), CameraSettings{}},
      {"perspective", glm::dmat3(1.0), perspective},
      {"oblique volume", rotation(30.0, 20.0), oblique},
      {"cropped", glm::dmat3(1.0), oblique, {0.2, 0.1, 0.3}, {0.7, 0.9, 0.6}},
  };
  const glm::ivec3 dims(40, 32, 24);
  auto ctx = test::headlessContext();
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Volume v =
        makeVolume(dims, makeWorldFromIndex({-20.0, -12.0, -18.0}, {1.0, 1.25, 1.5}, c.direction),
                   [](glm::dvec3) { return 1.0f; });
    VolumeRenderer renderer(*ctx, v);
    RenderSettings s = test::settingsOf({.mode = RenderMode::Mip, .size = {96, 80}});
    s.camera = c.camera;
    s.crop.min = c.cropMin;
    s.crop.max = c.cropMax;
    s.stepMm = 0.4;
    const Camera camera = renderer.render(s).camera;
    const glm::dvec3 lo = c.cropMin * glm::dvec3(dims) - 0.5;
    const glm::dvec3 hi = c.cropMax * glm::dvec3(dims) - 0.5;
    double expected = 0.0;
    int crossing = 0;
    for (int y = 0; y < s.size.y; ++y)
      for (int x = 0; x < s.size.x; ++x) {
        const glm::dvec2 ndc((x + 0.5) / s.size.x * 2 - 1, 1 - (y + 0.5) / s.size.y * 2);
        if (const auto chord = chordThroughBox(v, rayThrough(camera, ndc), lo, hi, 0.0)) {
          expected += *chord / s.stepMm;
          ++crossing;
        }
      }
    EXPECT_GT(crossing, 500);
    EXPECT_NEAR(renderer.nominalSamples(s), expected, 1e-9 * expected);
  }
}

// A ray that crosses the box and meets nothing writes the same background, to the bit, as the
// clear leaves where no ray runs: a sphere in a box, rays past the sphere inside the box and
// rays outside it, for a background whose 8-bit values sit halfway between two levels.
TEST(Raycast, TheClearedBackgroundEqualsWhatARayThatMeetsNothingWrites) {
  const Volume v = makeVolume({48, 48, 48}, test::axisGrid({-24, -24, -24}, {1, 1, 1}),
                              [](glm::dvec3 p) { return glm::length(p) < 10.0 ? 100.0f : 0.0f; });
  test::Renderer renderer(v);
  for (RenderMode mode : {RenderMode::Isosurface, RenderMode::Composite}) {
    SCOPED_TRACE(toString(mode));
    RenderSettings s = test::settingsOf({.mode = mode, .size = {128, 128}, .jitterOff = true});
    s.iso = 50.0;
    s.transfer.points = {{40.0, {1.0f, 0.8f, 0.6f, 0.0f}}, {60.0, {1.0f, 0.8f, 0.6f, 0.5f}}};
    s.camera.zoom = 0.7;  // the box well inside the image
    s.camera.azimuthDeg = 20.0;
    s.background = glm::vec3(0.3f, 127.5f / 255.0f, 178.5f / 255.0f);
    const RenderedFrame f = renderer.render(s);
    int outside = 0, insidePastTheSphere = 0, differing = 0;
    const auto* corner = f.image.pixel(0, 0);
    for (int y = 0; y < s.size.y; ++y)
      for (int x = 0; x < s.size.x; ++x) {
        const glm::dvec2 ndc((x + 0.5) / s.size.x * 2 - 1, 1 - (y + 0.5) / s.size.y * 2);
        const WorldRay ray = rayThrough(f.camera, ndc);
        const double along = glm::dot(-ray.origin, ray.direction);
        const double rho =
            std::sqrt(std::max(0.0, glm::dot(ray.origin, ray.origin) - along * along));
        if (rho < 14.0) continue;  // near the sphere
        const auto chord = chordThroughBox(v, ray, glm::dvec3(-0.5), glm::dvec3(47.5), 1e-3);
        if (chord && *chord < 2.0) continue;  // grazing the box
        ++(chord ? insidePastTheSphere : outside);
        const auto* p = f.image.pixel(x, y);
        if (p[0] != corner[0] || p[1] != corner[1] || p[2] != corner[2]) ++differing;
      }
    std::cout << toString(mode) << ": background " << int(corner[0]) << " " << int(corner[1]) << " "
              << int(corner[2]) << "; " << insidePastTheSphere
              << " rays past the sphere in the box, " << outside << " outside it, " << differing
              << " differing\n";
    EXPECT_GT(insidePastTheSphere, 1000);
    EXPECT_GT(outside, 1000);
    EXPECT_EQ(differing, 0);
  }
}

}  // namespace
}  // namespace mvw::render
