// Maximum intensity projection against a real CT: along the slice axis every ray meets the
// voxel centres of one column, so the picture must equal the CT's maximum projection.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/TestUtil.h"
#include "BlockGrid.h"
#include "RenderTestUtil.h"
#include "Trilinear.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

TEST(Raycast, MipAlongTheSliceAxisEqualsTheCtMaximumProjection) {
  const Volume ct = test::sampleCranium();
  const glm::ivec3 d = ct.dimensions();
  test::Renderer renderer(ct);
  RenderSettings s = test::settingsOf({.mode = RenderMode::Mip, .size = {d.x, d.y}});
  // Superior view: screen right = patient right (-x, i decreasing), screen down = +y (j).
  s.camera.view = StandardView::Superior;
  s.camera.zoom = framingSphere(ct).radius / (0.5 * d.y * ct.spacing().y);  // one pixel per voxel
  s.jitter = false;
  s.stepMm = ct.spacing().z;  // with midpoint sampling every sample is a voxel centre
  const RenderedFrame f = renderer.render(s);
  const auto [lo, hi] = ct.valueRange();
  double mse = 0.0;
  int worst = 0;
  for (int r = 0; r < d.y; ++r)
    for (int c = 0; c < d.x; ++c) {
      const int i = d.x - 1 - c, j = r;
      double m = -1e30;
      for (int k = 0; k < d.z; ++k) m = std::max(m, ct.value(i, j, k));
      const double expected = std::clamp((m - lo) / (hi - lo), 0.0, 1.0) * 255.0;
      const double got = f.image.pixel(c, r)[0];
      mse += (got - expected) * (got - expected);
      worst = std::max(worst, static_cast<int>(std::abs(got - expected) + 0.5));
    }
  mse /= d.x * d.y;
  const double psnr = 10.0 * std::log10(255.0 * 255.0 / std::max(mse, 1e-12));
  std::cout << "MIP vs max projection: PSNR " << psnr << " dB, worst pixel " << worst << "/255\n";
  // Measured on llvmpipe: 58.9 dB, worst 1/255 (rounding of the 8-bit output). A margin of 3 dB
  // for other GL implementations; a wrong sample, window or axis costs tens of dB.
  EXPECT_GE(psnr, 55.0);
  EXPECT_LE(worst, 1);
}

// MIP skips blocks by the maximum so far and by a bound that a pre-pass over every 16th sample
// finds; MinIP by the minimum so far. Values and depths against the same rays marched on the CPU
// (every sample, no skipping), from oblique directions, with the full value range and a narrow
// window. A skipped block that held a ray's extreme changes its pixel by many grey levels.
TEST(Raycast, MipAndMinIpSkippingLosesNoRaysExtreme) {
  const Volume ct = test::sampleCranium();
  const glm::ivec3 d = ct.dimensions();
  std::vector<double> values(static_cast<std::size_t>(d.x) * d.y * d.z);
  for (int k = 0, n = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) values[n++] = ct.value(i, j, k);
  const glm::dmat4 indexFromWorld = glm::inverse(ct.worldFromIndex());
  test::Renderer renderer(ct);
  const auto [lo, hi] = ct.valueRange();
  int worst = 0;
  std::size_t off = 0, pixels = 0, depths = 0, depthsOff = 0;
  for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp})
    for (const auto& [window, level] : {std::pair{hi - lo, 0.5 * (lo + hi)}, {400.0, 40.0}})
      for (const auto& [azimuth, elevation] :
           {std::pair{0.0, 0.0}, {37.0, 12.0}, {118.0, -35.0}, {250.0, 64.0}}) {
        RenderSettings s = test::settingsOf({.mode = mode, .size = {96, 96}, .jitterOff = true});
        s.window = {window, level};
        s.camera.azimuthDeg = azimuth;
        s.camera.elevationDeg = elevation;
        const RenderedFrame f = renderer.render(s);
        const double step = defaultStepMm(ct);
        for (int y = 0; y < s.size.y; ++y)
          for (int x = 0; x < s.size.x; ++x) {
            const glm::dvec2 ndc((x + 0.5) / s.size.x * 2 - 1, 1 - (y + 0.5) / s.size.y * 2);
            const WorldRay ray = rayThrough(f.camera, ndc);
            const glm::dvec3 o(indexFromWorld * glm::dvec4(ray.origin, 1.0));
            const glm::dvec3 dir(indexFromWorld * glm::dvec4(ray.direction, 0.0));
            const auto span =
                test::rayThroughIndexBox(ct, ray, glm::dvec3(-0.5), glm::dvec3(d) - 0.5);
            if (!span) continue;
            const auto [tNear, tFar] = *span;
            if (tFar - tNear < 4.0 * step) continue;  // misses or grazes the box
            // The extreme, where it lies, and whether a sample more than a step from it comes
            // within a tenth of a unit (then float rounding may pick either: no depth check).
            const double sign = mode == RenderMode::Mip ? 1.0 : -1.0;
            double extreme = -1e30, where = -1.0;
            std::vector<std::pair<double, double>> samples;
            for (double t = tNear + 0.5 * step; t <= tFar; t += step) {
              // As the GL samples, clamped to the edge voxels.
              const double v =
                  sign * resampling::detail::trilinear(
                             values.data(), d,
                             glm::clamp(o + t * dir, glm::dvec3(0.0), glm::dvec3(d - 1)));
              samples.emplace_back(t, v);
              if (v > extreme) {
                extreme = v;
                where = t;
              }
            }
            bool tied = false;
            for (const auto& [t, v] : samples)
              tied = tied || (std::abs(t - where) > 1.5 * step && v > extreme - 0.1);
            if (!tied) {
              ++depths;
              depthsOff +=
                  std::abs(f.image.depth[std::size_t(y) * s.size.x + x] - where) > 1.5 * step;
            }
            extreme *= sign;
            const double expected =
                std::clamp((extreme - (level - 0.5 * window)) / window, 0.0, 1.0) * 255.0;
            const int diff = static_cast<int>(std::abs(f.image.pixel(x, y)[0] - expected) + 0.5);
            worst = std::max(worst, diff);
            off += diff > 1;
            ++pixels;
          }
      }
  std::cout << "MIP/MinIP against CPU rays: " << pixels << " pixels, " << off
            << " off by more than 1 grey level, worst " << worst
            << "; depth of the extreme: " << depthsOff << " of " << depths
            << " more than a step off\n";
  EXPECT_GT(pixels, 30000u);
  // Measured on llvmpipe: worst 1 (8-bit output; the GL's filter weights are fixed-point).
  // Sample positions rounded differently may flip a level on a steep edge: a few allowed.
  EXPECT_LE(off, pixels / 2000);
  EXPECT_LE(worst, 3);
  // The depth reported is that of the first extreme: the same sample as on the CPU, where no
  // other comes within a tenth of a unit of it.
  EXPECT_GT(depths, pixels / 4);
  EXPECT_LE(depthsOff, depths / 1000);
}

// MIP's level maps (BlockGrid::prepareMipLevels, by chessboardDistance) against the definition:
// for every block, the least Chebyshev distance to a block whose maximum is at or above the
// level (a block at the level counts), at most 255. Random grids of 1-14 blocks a side, block
// maxima drawn from a few values so that levels fall on them, every level from under all to
// over all of them; and a long grid where the distance reaches the cap.
TEST(Raycast, MipLevelMapIsTheChebyshevDistanceToTheNearestBlockAtOrAboveTheLevel) {
  std::mt19937 random(53);
  std::vector<glm::ivec3> grids;
  for (int i = 0; i < 60; ++i)
    grids.emplace_back(1 + random() % 14, 1 + random() % 14, 1 + random() % 14);
  grids.emplace_back(300, 2, 3);
  int cases = 0, nonzero = 0;
  for (const glm::ivec3 n : grids) {
    std::vector<glm::vec2> minMax(static_cast<std::size_t>(n.x) * n.y * n.z);
    std::uniform_int_distribution<int> value(0, 40);
    for (glm::vec2& r : minMax) {
      const int v = value(random);
      r = glm::vec2(-1000.0f, v < 38 ? float(v) : -3.4e38f);  // a few blocks of NaN alone
    }
    if (n.x == 300) {  // one block above the rest at an end: distances up to 299, capped
      for (glm::vec2& r : minMax) r.y = 0.0f;
      minMax[0].y = 10.0f;
    }
    for (const float level : {-5.0f, 0.0f, 10.0f, 30.0f, 36.5f, 37.0f, 50.0f}) {
      const std::vector<std::uint8_t> d = detail::distanceToMaximumAtLeast(minMax, n, level);
      const std::vector<std::uint8_t> expected =
          test::chebyshevDistanceByDefinition(n, [&](int b) { return minMax[b].y >= level; });
      int wrong = 0;
      for (std::size_t b = 0; b < d.size(); ++b) {
        wrong += d[b] != expected[b];
        nonzero += d[b] > 1 && d[b] < 255;
      }
      EXPECT_EQ(wrong, 0) << n.x << " x " << n.y << " x " << n.z << ", level " << level;
      ++cases;
    }
  }
  EXPECT_EQ(cases, 427);
  EXPECT_GT(nonzero, 1000);  // the maps reach past the neighbours, not only 0, 1 and 255
}

}  // namespace
}  // namespace mvw::render
