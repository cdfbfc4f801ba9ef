// The volumetric normal map (Seipel 2007, section 3.1), checked texel by texel.
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "mvw/core/Error.h"
#include "mvw/render/GlyphMap.h"

namespace mvw::render {
namespace {

glm::dvec3 periodic(glm::dvec3 d, double n) {
  for (int c = 0; c < 3; ++c) d[c] -= n * std::round(d[c] / n);
  return d;
}

TEST(GlyphMap, SixteenSeparateSpheresOfTheRequestedDiameter) {
  const GlyphMap map = makeGlyphMap({128, 16, 32.0, 7});
  ASSERT_EQ(map.centres.size(), 16u);
  EXPECT_DOUBLE_EQ(map.radius, 16.0);
  for (std::size_t a = 0; a < map.centres.size(); ++a)
    for (std::size_t b = a + 1; b < map.centres.size(); ++b)
      EXPECT_GE(glm::length(periodic(map.centres[a] - map.centres[b], 128)), 32.0) << a << "," << b;
  // Every texel inside a glyph: a unit normal pointing away from that glyph's centre, and
  // A = distance / radius. Outside: no glyph (A = -1, RGB = 0).
  std::vector<int> inside(map.centres.size(), 0);
  for (int k = 0; k < 128; ++k)
    for (int j = 0; j < 128; ++j)
      for (int i = 0; i < 128; ++i) {
        const glm::vec4& t = map.at(i, j, k);
        const glm::dvec3 p = glm::dvec3(i, j, k) + 0.5;
        std::size_t nearest = 0;
        double best = 1e30;
        for (std::size_t c = 0; c < map.centres.size(); ++c) {
          const double d = glm::length(periodic(p - map.centres[c], 128));
          if (d < best) best = d, nearest = c;
        }
        if (best <= map.radius) {
          ++inside[nearest];
          ASSERT_NEAR(t.a, best / map.radius, 1e-5);
          if (best > 0.5) {
            ASSERT_NEAR(glm::length(glm::dvec3(t)), 1.0, 1e-5);
            const glm::dvec3 away = glm::normalize(periodic(p - map.centres[nearest], 128));
            ASSERT_GT(glm::dot(glm::dvec3(t), away), 0.9999);
          }
        } else {
          ASSERT_EQ(t.a, -1.0f);
          ASSERT_EQ(glm::length(glm::vec3(t)), 0.0f);
        }
      }
  // Each sphere holds about (4/3) pi r^3 texels (a lattice count: within 2 %).
  const double volume = 4.0 / 3.0 * std::numbers::pi * std::pow(16.0, 3);
  for (int n : inside) EXPECT_NEAR(n, volume, 0.02 * volume);
}

// The renderer's compact form: the cell holding a point names the one glyph that can contain
// it, and the texels are what that glyph's centre gives (shaders/common/glyphs.glsl).
TEST(GlyphMap, CellsNameTheOneGlyphThatReachesThem) {
  for (const GlyphMapSettings& s :
       {GlyphMapSettings{128, 16, 32.0, 7}, GlyphMapSettings{63, 9, 13.0, 2}}) {
    const GlyphMap map = makeGlyphMap(s);
    ASSERT_EQ(map.cellSize, s.size % 2 == 0 ? 2 : 1);
    const int n = s.size / map.cellSize;
    ASSERT_EQ(map.cells.size(), static_cast<std::size_t>(n) * n * n);
    for (std::size_t a = 0; a < map.centres.size(); ++a)
      for (std::size_t b = a + 1; b < map.centres.size(); ++b)
        EXPECT_GT(glm::length(periodic(map.centres[a] - map.centres[b], s.size)),
                  s.diameter + std::sqrt(3.0) * map.cellSize);
    auto cellGlyph = [&](const glm::dvec3& p) {
      glm::ivec3 c(glm::floor(p / double(map.cellSize)));
      c = ((c % n) + n) % n;
      return int(map.cells[(static_cast<std::size_t>(c.z) * n + c.y) * n + c.x]);
    };
    // Every texel centre: inside a glyph exactly when its cell's glyph contains it, with the
    // texel's normal and A.
    for (int k = 0; k < s.size; ++k)
      for (int j = 0; j < s.size; ++j)
        for (int i = 0; i < s.size; ++i) {
          const glm::dvec3 p = glm::dvec3(i, j, k) + 0.5;
          const glm::vec4& t = map.at(i, j, k);
          const int g = cellGlyph(p);
          const glm::dvec3 d = g ? periodic(p - map.centres[g - 1], s.size) : glm::dvec3(1e9);
          const bool inside = g && glm::length(d) <= map.radius;
          ASSERT_EQ(inside, t.a >= 0.0f) << i << "," << j << "," << k;
          if (!inside) continue;
          ASSERT_NEAR(glm::length(d) / map.radius, t.a, 1e-5);
          if (glm::length(d) > 1e-6) {
            ASSERT_GT(glm::dot(glm::normalize(d), glm::dvec3(t)), 0.99999);
          }
        }
    // Points between texels too: a point within a radius of some glyph's centre is always in
    // a cell that names that glyph.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, s.size);
    int inside = 0;
    for (int trial = 0; trial < 200000; ++trial) {
      const glm::dvec3 p(u(rng), u(rng), u(rng));
      for (std::size_t c = 0; c < map.centres.size(); ++c)
        if (glm::length(periodic(p - map.centres[c], s.size)) <= map.radius) {
          ++inside;
          ASSERT_EQ(cellGlyph(p), int(c) + 1);
        }
    }
    EXPECT_GT(inside, 1000);
    // The renderer's call, without texels: the same glyphs and cells.
    const GlyphMap compact = makeGlyphMap(s, false);
    EXPECT_TRUE(compact.texels.empty());
    EXPECT_EQ(compact.centres, map.centres);
    EXPECT_EQ(compact.cells, map.cells);
  }
}

TEST(GlyphMap, RepeatsAlongEveryAxisAndFollowsTheSeed) {
  const GlyphMap map = makeGlyphMap({64, 6, 16.0, 3});
  for (int i = 0; i < 64; i += 7) {
    EXPECT_EQ(map.at(i, 5, 9), map.at(i + 64, 5, 9));
    EXPECT_EQ(map.at(3, i, 9), map.at(3, i - 64, 9));
    EXPECT_EQ(map.at(3, 5, i), map.at(3, 5, i + 128));
  }
  EXPECT_EQ(makeGlyphMap({64, 6, 16.0, 3}).texels, map.texels);
  EXPECT_NE(makeGlyphMap({64, 6, 16.0, 4}).centres, map.centres);
}

TEST(GlyphMap, ImpossibleRequestsAreErrors) {
  EXPECT_THROW(makeGlyphMap({32, 200, 15.0, 1}), Error);  // cannot fit without overlap
  EXPECT_THROW(makeGlyphMap({64, 4, 40.0, 1}), Error);    // wider than half the map
  EXPECT_THROW(makeGlyphMap({4, 1, 2.0, 1}), Error);
  EXPECT_THROW(makeGlyphMap({512, 256, 4.0, 1}), Error);  // one byte per cell names the glyph
}

// The blue-noise placement (jittered BCC lattice): periodic, glyphs never closer than a
// diameter plus the cell clearance, every point of the map within the promised coverage radius
// of a centre, the same map for the same seed.
TEST(GlyphMap, BlueNoiseIsPeriodicSeparatedCoveringAndSeeded) {
  for (double fraction : {0.5, 0.7, 0.84}) {
    GlyphMapSettings s;
    s.placement = GlyphPlacement::BlueNoise;
    s.diameter = fraction * blueNoiseSpacing(s.size);
    s.seed = 11;
    const GlyphMap map = makeGlyphMap(s);
    ASSERT_EQ(map.centres.size(), 250u);
    const double n = s.size;
    double nearest = 1e30;
    for (std::size_t a = 0; a < map.centres.size(); ++a) {
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(map.centres[a][c] >= 0.0 && map.centres[a][c] < n);
      for (std::size_t b = a + 1; b < map.centres.size(); ++b)
        nearest = std::min(nearest, glm::length(periodic(map.centres[a] - map.centres[b], n)));
    }
    EXPECT_GT(nearest, s.diameter + glyphClearance(s.size)) << fraction;
    // Jitter: not the bare lattice (whose nearest distance is the spacing exactly).
    EXPECT_LT(nearest, blueNoiseSpacing(s.size) - 1e-3) << fraction;
    // Coverage: random points and every texel centre lie within the coverage radius.
    const double cover = blueNoiseCoverage(s.size, s.diameter);
    EXPECT_LT(cover, 0.8 * blueNoiseSpacing(s.size));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, n);
    double worst = 0.0;
    for (int trial = 0; trial < 20000; ++trial) {
      const glm::dvec3 p(u(rng), u(rng), u(rng));
      double best = 1e30;
      for (const auto& c : map.centres) best = std::min(best, glm::length(periodic(p - c, n)));
      worst = std::max(worst, best);
    }
    EXPECT_LE(worst, cover) << fraction;
    // Periodic: the texels repeat along every axis.
    for (int i = 0; i < 128; i += 13) {
      EXPECT_EQ(map.at(i, 5, 9), map.at(i + 128, 5, 9));
      EXPECT_EQ(map.at(3, i, 9), map.at(3, i - 128, 9));
      EXPECT_EQ(map.at(3, 5, i), map.at(3, 5, i + 256));
    }
    // Deterministic by seed.
    EXPECT_EQ(makeGlyphMap(s, false).centres, map.centres);
    GlyphMapSettings other = s;
    other.seed = 12;
    EXPECT_NE(makeGlyphMap(other, false).centres, map.centres);
  }
}

// The renderer's compact cells hold for the blue-noise map too: a point inside a glyph is in a
// cell naming it.
TEST(GlyphMap, BlueNoiseCellsNameTheGlyphThatReachesThem) {
  const GlyphMapSettings s = blueNoiseGlyphMap(4.0, 3.0, 2);
  const GlyphMap map = makeGlyphMap(s, false);
  const int n = s.size / map.cellSize;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, s.size);
  int inside = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    glm::ivec3 c(glm::floor(p / double(map.cellSize)));
    c = ((c % n) + n) % n;
    const int g = map.cells[(static_cast<std::size_t>(c.z) * n + c.y) * n + c.x];
    for (std::size_t k = 0; k < map.centres.size(); ++k)
      if (glm::length(periodic(p - map.centres[k], s.size)) <= map.radius) {
        ++inside;
        ASSERT_EQ(g, int(k) + 1);
      }
  }
  // Glyphs of 0.75 spacing fill about 0.68 * 0.75^3 = 29 % of space.
  EXPECT_GT(inside, 20000);
  EXPECT_LT(inside, 36000);
}

// Spacing in mm sets the map's scale: the renderer's map voxels per mm are diameter / mm.
TEST(GlyphMap, BlueNoiseSpacingInMillimetres) {
  const GlyphMapSettings s = blueNoiseGlyphMap(5.0, 3.5, 1);
  const double voxelsPerMm = s.diameter / 3.5;
  EXPECT_NEAR(blueNoiseSpacing(s.size) / voxelsPerMm, 5.0, 1e-9);
  EXPECT_NEAR(maxBlueNoiseDiameterMm(5.0),
              5.0 * (1.0 - glyphClearance(s.size) / blueNoiseSpacing(s.size)), 1e-5);
  EXPECT_NO_THROW(blueNoiseGlyphMap(5.0, maxBlueNoiseDiameterMm(5.0), 1));
  EXPECT_NO_THROW(makeGlyphMap(blueNoiseGlyphMap(5.0, maxBlueNoiseDiameterMm(5.0), 1), false));
}

TEST(GlyphMap, BadBlueNoiseRequestsSayWhatFits) {
  try {
    blueNoiseGlyphMap(5.0, 5.0, 1);
    FAIL() << "a glyph as wide as its spacing was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at most 4.37"), std::string::npos) << e.what();
  }
  EXPECT_THROW(blueNoiseGlyphMap(0.0, 1.0, 1), Error);
  EXPECT_THROW(blueNoiseGlyphMap(4.0, -1.0, 1), Error);
  // The paper's map says how many random glyphs it fitted.
  try {
    makeGlyphMap({128, 40, 32.0, 1});
    FAIL() << "40 glyphs of 32 voxels were placed in 128^3";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fitted"), std::string::npos) << e.what();
  }
}

// The paper's own map stays reproducible: the same centres as before blue noise existed.
TEST(GlyphMap, PaperPlacementIsTheDefault) {
  EXPECT_EQ(GlyphMapSettings{}.placement, GlyphPlacement::Paper);
  const GlyphMap map = makeGlyphMap({128, 16, 32.0, 1}, false);
  ASSERT_EQ(map.centres.size(), 16u);
}

// `mvw glyphmap`'s volume: the texels as 4 float components, voxel for voxel, on cubic voxels.
TEST(GlyphMap, AsAVolume) {
  const GlyphMap map = makeGlyphMap({16, 2, 4.0, 3});
  const Volume v = glyphMapVolume(map, 0.5);
  EXPECT_EQ(v.dimensions(), glm::ivec3(16));
  EXPECT_EQ(v.components(), 4);
  EXPECT_EQ(v.scalarType(), ScalarType::Float32);
  EXPECT_EQ(v.spacing(), glm::dvec3(0.5));
  EXPECT_EQ(v.origin(), glm::dvec3(0.0));
  EXPECT_EQ(v.direction(), glm::dmat3(1.0));
  EXPECT_EQ(v.metadata().seriesDescription, "mvw glyph normal map");
  for (int k = 0; k < 16; k += 3)
    for (int j = 0; j < 16; j += 2)
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c)
          ASSERT_EQ(v.value(i, j, k, c), map.at(i, j, k)[c]) << i << "," << j << "," << k;
}

}  // namespace
}  // namespace mvw::render
