// Fused projections (issue 41): the functional volume's own projection along each ray over the
// anatomy's, in the overlay's colour map. Against the real Cranium CT and a PET-like volume on a
// grid of its own (twice the CT's spacing, placed by a registration that is not the identity):
// along the slice axis every ray meets one column of CT voxel centres, and the functional volume
// there at its own voxel centres or half way between two, so the CPU computes both projections
// exactly and the pixels through both colour maps.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "../support/TestUtil.h"
#include "RenderTestUtil.h"
#include "Trilinear.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/io/Png.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

// Where the functional world lies against the anatomical one: the registration undoes it.
const glm::dvec3 kMisplacement{7.0, -11.0, 5.0};

struct Lesion {
  glm::dvec3 centre;  // anatomical world, mm
  double peak;
};

// A PET-like volume over the CT: uptake 1 in a sphere of 85 mm about the framing centre (the
// head), 0 outside, and Gaussian lesions (sigma 6 mm) on top. Its voxel a lies at the CT's
// voxel 2a (anatomical world), moved by kMisplacement in its own world.
Volume petLike(const Volume& ct, const std::vector<Lesion>& lesions) {
  const glm::ivec3 d = ct.dimensions();
  const glm::ivec3 fd = d / 2 + 1;
  const glm::dmat4 worldFromIndex = glm::translate(glm::dmat4(1.0), kMisplacement) *
                                    ct.worldFromIndex() *
                                    glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
  const glm::dvec3 centre = framingSphere(ct).centre;
  return test::makeVolume(fd, worldFromIndex, [&](glm::dvec3 p) {
    const glm::dvec3 at = p - kMisplacement;
    double v = glm::length(at - centre) < 85.0 ? 1.0 : 0.0;
    for (const Lesion& l : lesions) {
      const glm::dvec3 r = at - l.centre;
      v += l.peak * std::exp(-glm::dot(r, r) / (2.0 * 6.0 * 6.0));
    }
    return static_cast<float>(v);
  });
}

glm::dmat4 anatomicalFromFunctional() { return glm::translate(glm::dmat4(1.0), -kMisplacement); }

// Superior view, one pixel per CT voxel, a sample at every CT voxel centre (mip_gltest.cpp).
RenderSettings alongTheSliceAxis(const Volume& ct, RenderMode mode) {
  const glm::ivec3 d = ct.dimensions();
  RenderSettings s = test::settingsOf(
      {.mode = mode, .size = {d.x, d.y}, .view = StandardView::Superior, .jitterOff = true});
  s.camera.zoom = framingSphere(ct).radius / (0.5 * d.y * ct.spacing().y);
  s.stepMm = ct.spacing().z;
  s.overlay.fusion = true;
  s.functionalWindow = {0.0, 8.0};
  s.overlay.opacity = 0.6f;
  s.overlay.threshold = 0.2f;
  s.overlayColors = io::standardColorTable(ColorMap::HotIron);  // nearest: entries as they are
  return s;
}

// The overlay's entry for the fraction u: the 256-texel table read nearest at u.
int entryOf(double u) { return std::clamp(static_cast<int>(std::floor(u * 256.0)), 0, 255); }

TEST(FusedProjection, AlongTheSliceAxisEqualsBothProjectionsThroughTheColourMaps) {
  const Volume ct = test::sampleCranium();
  const glm::ivec3 d = ct.dimensions();
  const glm::dvec3 c = framingSphere(ct).centre;
  const Volume pet =
      petLike(ct, {{c + glm::dvec3(20, -55, 10), 7.0}, {c + glm::dvec3(-25, 40, -12), 5.0}});
  std::vector<float> petValues(pet.dataAs<float>(), pet.dataAs<float>() + pet.voxelCount());
  test::Renderer renderer(ct);
  renderer.setFunctional(pet, anatomicalFromFunctional());
  const auto [lo, hi] = ct.valueRange();
  const glm::dmat4 petIndexFromAnatomical =
      glm::inverse(pet.worldFromIndex()) * glm::inverse(anatomicalFromFunctional());
  struct Case {
    RenderMode mode;
    FusionProjection projection;
  };
  for (const Case& k : {Case{RenderMode::Mip, FusionProjection::Max},
                        Case{RenderMode::MinIp, FusionProjection::Max},
                        Case{RenderMode::Average, FusionProjection::Max},
                        Case{RenderMode::Average, FusionProjection::Mean}}) {
    RenderSettings s = alongTheSliceAxis(ct, k.mode);
    s.overlay.projection = k.projection;
    // The mean along a ray is the head's uptake (1 of 8) times the part of the ray inside it,
    // and a lesion's share: a lower threshold, so that the head's middle shows.
    if (k.projection == FusionProjection::Mean) s.overlay.threshold = 0.06f;
    const RenderedFrame f = renderer.render(s);
    const ColorTable& table = *s.overlayColors;
    double mse = 0.0;
    int worst = 0, fused = 0;
    for (int r = 0; r < d.y; ++r)
      for (int col = 0; col < d.x; ++col) {
        const int i = d.x - 1 - col, j = r;
        double anatomy = k.mode == RenderMode::Mip ? -1e30 : k.mode == RenderMode::MinIp ? 1e30 : 0;
        double fMax = -1.0, fSum = 0.0;
        for (int z = 0; z < d.z; ++z) {
          const double v = ct.value(i, j, z);
          anatomy = k.mode == RenderMode::Mip     ? std::max(anatomy, v)
                    : k.mode == RenderMode::MinIp ? std::min(anatomy, v)
                                                  : anatomy + v;
          const glm::dvec3 at(petIndexFromAnatomical *
                              glm::dvec4(ct.worldFromIndexPoint({i, j, z}), 1.0));
          const double u = resampling::detail::trilinear(petValues.data(), pet.dimensions(), at) /
                           (s.functionalWindow.high - s.functionalWindow.low);
          fSum += u;
          if (u > s.overlay.threshold) fMax = std::max(fMax, std::clamp(u, 0.0, 1.0));
        }
        if (k.mode == RenderMode::Average) anatomy /= d.z;
        const double grey = std::clamp((anatomy - lo) / (hi - lo), 0.0, 1.0);
        const double u = k.projection == FusionProjection::Mean ? fSum / d.z : fMax;
        const bool shown =
            k.projection == FusionProjection::Mean ? u > s.overlay.threshold : fMax >= 0.0;
        // The table's entry at u; where u lies within float rounding of an entry boundary
        // (1e-4 of the range: the GPU sums a mean of some 100 samples in float), the entry on
        // the boundary's other side is as right, and the nearer of the two colours counts.
        auto expectedWith = [&](int entry) {
          if (!shown) return glm::dvec3(grey);
          const auto& e = table.rgb[static_cast<std::size_t>(std::clamp(entry, 0, 255))];
          return glm::mix(glm::dvec3(grey), glm::dvec3(e[0], e[1], e[2]) / 255.0,
                          double(s.overlay.opacity));
        };
        if (shown) ++fused;
        const auto* px = f.image.pixel(col, r);
        double best = 1e30;
        int bestWorst = 0;
        for (int entry : {entryOf(u - 1e-4), entryOf(u + 1e-4)}) {
          const glm::dvec3 expected = expectedWith(entry);
          double se = 0.0;
          int w = 0;
          for (int ch = 0; ch < 3; ++ch) {
            const double want = expected[ch] * 255.0, got = px[ch];
            se += (got - want) * (got - want);
            w = std::max(w, static_cast<int>(std::abs(got - want) + 0.5));
          }
          if (se < best) best = se, bestWorst = w;
        }
        mse += best;
        worst = std::max(worst, bestWorst);
      }
    mse /= 3.0 * d.x * d.y;
    const double psnr = 10.0 * std::log10(255.0 * 255.0 / std::max(mse, 1e-12));
    std::cout << toString(k.mode) << (k.projection == FusionProjection::Mean ? " (mean)" : "")
              << " fused vs both projections: PSNR " << psnr << " dB, worst " << worst << "/255, "
              << fused << " pixels fused\n";
    // Both branches of the blend are checked: fused pixels (the lesions' discs, or the head's
    // middle for the mean) and plain ones around them.
    EXPECT_GT(fused, 500) << "the lesions must show";
    EXPECT_LT(fused, d.x * d.y - 500) << "the anatomy must show around them";
    // As mip_gltest.cpp's MIP against the CT's maximum projection: 3 dB below what llvmpipe
    // gives, and a pixel off by the output's rounding at most.
    EXPECT_GE(psnr, 55.0);
    EXPECT_LE(worst, 1);
  }
}

// Fusion asked where the functional volume lies below the threshold everywhere: the fused
// programs (which skip only where neither volume can change the projection, and read the
// second volume in a loop of their own) show the very pixels of the plain ones.
TEST(FusedProjection, NothingAboveTheThresholdLeavesThePlainProjection) {
  const Volume ct = test::sampleCranium();
  test::Renderer renderer(ct);
  renderer.setFunctional(petLike(ct, {}), anatomicalFromFunctional());
  for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Average})
    for (bool cue : {false, true}) {
      if (cue && mode != RenderMode::Mip) continue;
      RenderSettings s = test::settingsOf({.mode = mode, .size = {97, 83}});
      s.camera.azimuthDeg = 33;
      s.camera.elevationDeg = 12;
      s.window = {1500, 300};
      s.depthCue.on = cue;
      s.depthCue.amount = cue ? 0.66 : 0.0;
      s.depthCue.contrast = cue ? 0.33 : 1.0;
      s.functionalWindow = {0.0, 1.0};
      s.overlay.threshold = 1.0f;  // the uptake is 1 at most: no sample lies above it
      const RenderedFrame plain = renderer.render(s);
      s.overlay.fusion = true;
      const RenderedFrame fused = renderer.render(s);
      EXPECT_EQ(plain.image.rgba, fused.image.rgba) << toString(mode) << (cue ? " cued" : "");
      s.overlay.threshold = 0.5f;  // the head's uptake now shows
      EXPECT_NE(renderer.render(s).image.rgba, plain.image.rgba) << toString(mode);
    }
}

// Two equal lesions, one in the front of the head and one at its back as seen from the front:
// without a depth cue their fused colours are the same; with it the front one takes a higher
// (brighter) entry of the colour map than the back one, and seen from behind the order turns.
TEST(FusedProjection, DepthCueShowsALesionInFrontBrighterThanOneBehind) {
  const Volume ct = test::sampleCranium();
  const glm::dvec3 c = framingSphere(ct).centre;
  // Anterior is -y in LPS; the two lie 50 mm apart side to side, so both show from the front.
  const glm::dvec3 front = c + glm::dvec3(25, -60, 15), back = c + glm::dvec3(-25, 60, 15);
  test::Renderer renderer(ct);
  renderer.setFunctional(petLike(ct, {{front, 7.0}, {back, 7.0}}), anatomicalFromFunctional());
  const ColorTable table = io::standardColorTable(ColorMap::HotIron);
  // The entry of the table a pixel shows, from its colour and the anatomy's grey under it
  // (the overlay's opacity 1: the colour itself).
  auto entryAt = [&](const RenderedFrame& f, const glm::dvec3& world) {
    const glm::dvec4 clip = f.camera.clipFromWorld * glm::dvec4(world, 1.0);
    const int x = static_cast<int>((clip.x / clip.w * 0.5 + 0.5) * f.image.width);
    const int y = static_cast<int>((0.5 - clip.y / clip.w * 0.5) * f.image.height);
    const auto* px = f.image.pixel(x, y);
    int best = 0, bestDistance = 1 << 30;
    for (int e = 0; e < 256; ++e) {
      int distance = 0;
      for (int ch = 0; ch < 3; ++ch) distance += std::abs(int(table.rgb[e][ch]) - int(px[ch]));
      if (distance < bestDistance) best = e, bestDistance = distance;
    }
    EXPECT_LE(bestDistance, 3) << "not a colour of the table";
    return best;
  };
  RenderSettings s =
      test::settingsOf({.mode = RenderMode::Mip, .size = {321, 321}, .jitterOff = true});
  s.overlay.fusion = true;
  s.functionalWindow = {0.0, 8.0};
  s.overlay.opacity = 1.0f;
  s.overlay.threshold = 0.3f;
  s.overlayColors = table;
  // The renders, to look at (docs/user-guide/depth-cue.md shows them).
  const std::filesystem::path out = std::filesystem::path(MVW_TEST_OUTPUT_DIR) / "fused-projection";
  std::filesystem::create_directories(out);
  for (StandardView view : {StandardView::Anterior, StandardView::Posterior}) {
    const std::string side = view == StandardView::Anterior ? "front" : "behind";
    s.camera.view = view;
    s.depthCue.on = false;
    const RenderedFrame plain = renderer.render(s);
    const int plainFront = entryAt(plain, front), plainBack = entryAt(plain, back);
    EXPECT_NEAR(plainFront, plainBack, 2) << "equal lesions, no cue";
    EXPECT_GT(plainFront, 200);  // peak 8 of 8: the top of the map
    s.depthCue.on = true;
    s.depthCue.brightness = 0.0;
    s.depthCue.amount = 0.66;
    s.depthCue.contrast = 0.33;
    const RenderedFrame cued = renderer.render(s);
    io::writePng(plain.image, out / ("fused-mip-from-" + side + ".png"));
    io::writePng(cued.image, out / ("fused-mip-depth-cued-from-" + side + ".png"));
    // The same in the "pet" colour map, whose hues part the two entries at a glance.
    RenderSettings pet = s;
    pet.overlayColors = io::standardColorTable(ColorMap::Pet);
    io::writePng(renderer.render(pet).image,
                 out / ("fused-mip-depth-cued-pet-from-" + side + ".png"));
    pet.depthCue.on = false;
    io::writePng(renderer.render(pet).image, out / ("fused-mip-pet-from-" + side + ".png"));
    const int nearer = entryAt(cued, view == StandardView::Anterior ? front : back);
    const int farther = entryAt(cued, view == StandardView::Anterior ? back : front);
    std::cout << (view == StandardView::Anterior ? "from the front" : "from behind") << ": no cue "
              << plainFront << " / " << plainBack << ", cued nearer " << nearer << " farther "
              << farther << "\n";
    // The lesions' centres lie 120 mm apart along the ray, 2R about 280 mm: the cue (0.33 at
    // the back of the sphere, 0.99 at its front) parts them by a good fifth of the map.
    EXPECT_GT(nearer, farther + 40);
    EXPECT_LT(nearer, plainFront + 1);
  }
}

}  // namespace
}  // namespace mvw::render
