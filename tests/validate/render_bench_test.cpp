// The feature bench's logic (mvw/validate/RenderBench.h) without GL: which views it measures,
// their names in its table, the view without its features, and the median of the ratios.
#include <gtest/gtest.h>

#include "mvw/validate/RenderBench.h"

namespace mvw::validate {
namespace {

TEST(RenderBench, PlainViewHasNoFeature) {
  const render::RenderSettings s;
  EXPECT_FALSE(hasBenchFeature(s));
  EXPECT_EQ(benchFeatureName(s), "");
}

TEST(RenderBench, FeaturesAreNamedInOrder) {
  render::RenderSettings s;
  s.depthCue.on = true;
  EXPECT_TRUE(hasBenchFeature(s));
  EXPECT_EQ(benchFeatureName(s), "depth cue");
  s.glyphs.on = true;
  s.overlay.fusion = true;
  EXPECT_EQ(benchFeatureName(s), "glyphs+fusion+depth cue");
  s.glyphs.on = false;
  EXPECT_EQ(benchFeatureName(s), "fusion+depth cue");
}

TEST(RenderBench, AnatomyOnACutFaceCountsOnlyWhenCropped) {
  render::RenderSettings s;
  s.mode = render::RenderMode::Composite;
  s.cutFace = render::CutFace::Anatomy;
  EXPECT_FALSE(hasBenchFeature(s));  // no crop: no cut face
  s.crop.min = glm::dvec3(0.25, 0.0, 0.0);
  EXPECT_TRUE(hasBenchFeature(s));
  EXPECT_EQ(benchFeatureName(s), "cut face");
  s.glyphs.on = true;
  EXPECT_EQ(benchFeatureName(s), "glyphs+cut face");
}

TEST(RenderBench, WithoutFeaturesKeepsTheRest) {
  render::RenderSettings s;
  s.glyphs.on = s.overlay.fusion = s.depthCue.on = true;
  s.cutFace = render::CutFace::Anatomy;
  s.crop.min = glm::dvec3(0.25, 0.0, 0.0);
  s.size = {64, 48};
  const render::RenderSettings w = withoutBenchFeatures(s);
  EXPECT_FALSE(hasBenchFeature(w));
  EXPECT_EQ(w.cutFace, render::CutFace::Plain);
  EXPECT_EQ(w.size, s.size);
  EXPECT_EQ(w.crop.min, s.crop.min);
}

TEST(RenderBench, Median) {
  EXPECT_DOUBLE_EQ(median({3.0}), 3.0);
  EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 2.0, 3.0}), 2.5);
}

}  // namespace
}  // namespace mvw::validate
