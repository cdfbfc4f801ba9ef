// Needs a GL context (headless: MVW_GL chooses, auto by default): every program the ray
// caster can make compiles and links, each feature's uniforms are the program's, and
// raycast/template.glsl stops a wrong combination of its loop macros (common/glyphs.glsl two
// glyph shadings) at compile time, saying what to define.
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "RaycastPrograms.h"
#include "mvw/core/Error.h"
#include "mvw/core/RenderMode.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render {
namespace {

using detail::featureCounts;
using detail::GlyphShading;
using detail::kMaxFeatureValues;
using detail::RaycastFeature;
using detail::raycastFeatures;
using detail::RaycastFeatureSpec;
using detail::RaycastPrograms;
using detail::RaycastSource;
using detail::RaycastVariants;
using detail::VolumeLayout;

std::string describe(const RaycastSource& s) {
  std::string out = s.vertex + " + ";
  for (const std::string& i : s.includes) out += i + " + ";
  out += s.fragment + " with {";
  for (std::size_t i = 0; i < s.defines.size(); ++i) out += (i ? ", " : "") + s.defines[i];
  return out + "}";
}

// One program per mode, layout and combination of the features' values, compiled and linked
// as the renderer does (ShaderProgram), each named on failure by its files and defines. 877
// programs, mostly composite with glyphs (composite and isosurface each with and without the
// cut face since issue 36): a variant that no view in the golden suite uses breaks here, not in
// a user's first frame. (1,645 while the glyph shading was three bits: 768 of them combined
// two shadings, which no settings asked for.)
TEST(RaycastPrograms, EveryProgramCompilesAndLinks) {
  auto ctx = createHeadlessContext({1, 1});
  const std::vector<RaycastSource> every = RaycastPrograms::every();
  int failed = 0;
  for (const RaycastSource& s : every) {
    try {
      ShaderProgram program(s.vertex, s.fragment, s.defines, s.includes);
    } catch (const Error& e) {
      if (++failed <= 10) ADD_FAILURE() << describe(s) << ": " << e.what();
    }
  }
  RecordProperty("programs", static_cast<int>(every.size()));
  EXPECT_EQ(failed, 0) << "of " << every.size() << " programs";
}

// The variant with every feature at `value` (at most its last), so that a feature that needs
// another (glyph kinds need glyphs) counts.
RaycastVariants everyFeatureAt(int value) {
  RaycastVariants v;
  for (const RaycastFeatureSpec& f : raycastFeatures()) v.set(f.id, std::min(value, f.values - 1));
  return v;
}

std::vector<RenderMode> rayCastModes() {
  std::vector<RenderMode> out;
  for (const std::string& name : renderModeNames())
    if (!isShellMode(*parseRenderMode(name))) out.push_back(*parseRenderMode(name));
  return out;
}

// The enumeration holds each fragment shader forMode uses, and no feature's value is dead:
// each changes some program's defines or includes, so a value the table gives no define or
// include, or a mode list that leaves the feature out everywhere, shows here.
TEST(RaycastPrograms, EveryFeatureValueAndLayoutChangesAProgram) {
  std::vector<std::string> fragments;
  for (const RaycastSource& s : RaycastPrograms::every()) fragments.push_back(s.fragment);
  for (const char* f : {"composite.frag.glsl", "isosurface.frag.glsl", "projection.frag.glsl",
                        "mpr.frag.glsl", "beta.frag.glsl"})
    EXPECT_NE(std::find(fragments.begin(), fragments.end(), f), fragments.end()) << f;
  const auto& features = raycastFeatures();
  for (std::size_t i = 0; i < features.size(); ++i) {
    const RaycastFeatureSpec& f = features[i];
    EXPECT_EQ(static_cast<std::size_t>(f.id), i) << f.name << ": out of RaycastFeature's order";
    EXPECT_EQ(f.defines[0], nullptr) << f.name << ": off must add no define";
    for (int value = 1; value < f.values; ++value) {
      bool changes = false;
      for (RenderMode mode : rayCastModes())
        for (int l = 0; l < static_cast<int>(VolumeLayout::Count); ++l) {
          const auto layout = static_cast<VolumeLayout>(l);
          RaycastVariants on = everyFeatureAt(1);
          on.set(f.id, value);
          RaycastVariants off = on;
          off.set(f.id, 0);
          const RaycastSource a = RaycastPrograms::source(mode, layout, on);
          const RaycastSource b = RaycastPrograms::source(mode, layout, off);
          if (a.defines != b.defines || a.includes != b.includes) changes = true;
        }
      EXPECT_TRUE(changes) << f.name << " = " << value << " changes no program";
    }
  }
  for (int l = 1; l < static_cast<int>(VolumeLayout::Count); ++l)
    EXPECT_NE(
        RaycastPrograms::source(RenderMode::Composite, static_cast<VolumeLayout>(l), {}).defines,
        RaycastPrograms::source(RenderMode::Composite, VolumeLayout::Gradient, {}).defines)
        << "layout " << l;
}

// Each uniform a feature names (its own and the shared ones) is read by its program, in some
// mode it applies to, with the feature at its last value and nothing else on but what it needs:
// the table cannot name a uniform its shaders dropped.
TEST(RaycastPrograms, EachFeaturesUniformsAreItsProgramsOwn) {
  auto ctx = createHeadlessContext({1, 1});
  for (const RaycastFeatureSpec& f : raycastFeatures()) {
    EXPECT_EQ(f.uniforms.empty(), f.setUniforms == nullptr) << f.name << ": own uniforms, a setter";
    std::vector<std::string> missing(f.uniforms.begin(), f.uniforms.end());
    missing.insert(missing.end(), f.sharedUniforms.begin(), f.sharedUniforms.end());
    if (missing.empty()) continue;
    RaycastVariants v;
    v.set(f.id, f.values - 1);
    if (f.needs != RaycastFeature::Count) v.set(f.needs, 1);
    for (RenderMode mode : rayCastModes()) {
      if (!f.appliesTo(mode)) continue;
      const RaycastSource s = RaycastPrograms::source(mode, VolumeLayout::Gradient, v);
      const ShaderProgram program(s.vertex, s.fragment, s.defines, s.includes);
      std::erase_if(missing, [&](const std::string& u) { return program.uniform(u.c_str()) >= 0; });
    }
    for (const std::string& u : missing) ADD_FAILURE() << f.name << ": no program reads " << u;
  }
}

// A feature's own uniforms (set by its setUniforms only where it counts) are read by no program
// where it does not count: every other feature at its last value with this one off, this one
// at its last value without the feature it needs, and in each mode it does not apply to. A
// shader reading one of them elsewhere would see it unset.
TEST(RaycastPrograms, AFeaturesOwnUniformsAreReadOnlyWhereItCounts) {
  auto ctx = createHeadlessContext({1, 1});
  int checked = 0;
  for (const RaycastFeatureSpec& f : raycastFeatures()) {
    if (f.uniforms.empty()) continue;
    std::vector<RaycastVariants> without;
    RaycastVariants others = everyFeatureAt(kMaxFeatureValues);
    others.set(f.id, 0);
    without.push_back(others);
    RaycastVariants needsOff = everyFeatureAt(kMaxFeatureValues);
    if (f.needs != RaycastFeature::Count) {
      needsOff.set(f.needs, 0);
      without.push_back(needsOff);
    }
    for (RenderMode mode : rayCastModes())
      for (const RaycastVariants& v :
           f.appliesTo(mode) ? without : std::vector{everyFeatureAt(kMaxFeatureValues)}) {
        ASSERT_FALSE(featureCounts(f, mode, v));
        const RaycastSource s = RaycastPrograms::source(mode, VolumeLayout::Gradient, v);
        const ShaderProgram program(s.vertex, s.fragment, s.defines, s.includes);
        for (const char* u : f.uniforms)
          EXPECT_LT(program.uniform(u), 0) << f.name << ": " << describe(s) << " reads " << u;
        ++checked;
      }
  }
  EXPECT_GT(checked, 0);
}

// The settings' glyph convexity, labels and kinds give one shading (GlyphShading), and the
// features read the settings only through their valueFor.
TEST(RaycastFeatures, GlyphSettingsGiveOneShading) {
  auto shadingOf = [](const RenderSettings& s) {
    return RaycastPrograms::variants(s, false).glyphShading();
  };
  RenderSettings s;
  s.glyphs.on = true;
  EXPECT_EQ(shadingOf(s), GlyphShading::Bumps);
  s.glyphs.convexity = GlyphConvexity::Dimples;
  EXPECT_EQ(shadingOf(s), GlyphShading::Dimples);
  s.glyphs.convexity = GlyphConvexity::Both;
  EXPECT_EQ(shadingOf(s), GlyphShading::Both);
  // Chosen labels carry their own bump or dimple through the "both" shading...
  s.glyphs.convexity = GlyphConvexity::Dimples;
  s.glyphLabels = {{1, GlyphKind::Dimples, "a"}, {2, GlyphKind::Bumps, "b"}};
  EXPECT_EQ(shadingOf(s), GlyphShading::Both);
  // ...and a kind beyond those two takes the kinds' shading, as kinds for the classes do.
  s.glyphLabels.push_back({3, GlyphKind::Rings, "c"});
  EXPECT_EQ(shadingOf(s), GlyphShading::Kinds);
  s.glyphLabels.clear();
  s.glyphs.classKinds = {GlyphKind::Bumps};
  EXPECT_EQ(shadingOf(s), GlyphShading::Kinds);
  // Glyphs off: the shading's define reaches no program.
  s.glyphs.on = false;
  const RaycastSource off = RaycastPrograms::source(RenderMode::Composite, VolumeLayout::Gradient,
                                                    RaycastPrograms::variants(s, false));
  EXPECT_EQ(std::count(off.defines.begin(), off.defines.end(), "MVW_GLYPH_KINDS 1"), 0);
}

// Defines set as a mode file or a wrong variant would set them, prepended to plain MIP's
// program (whose own loop macros, RAY_PREPASS alone, allow them; `base`: another mode's): the
// compile must fail with the shaders' message.
void expectCompileError(const std::vector<std::string>& defines, const std::string& message,
                        RaycastSource s = RaycastPrograms::source(RenderMode::Mip,
                                                                  VolumeLayout::Gradient, {})) {
  s.defines.insert(s.defines.end(), defines.begin(), defines.end());
  try {
    ShaderProgram program(s.vertex, s.fragment, s.defines, s.includes);
    ADD_FAILURE() << describe(s) << " compiled; expected an error saying \"" << message << "\"";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
        << describe(s) << ": " << e.what();
  }
}

TEST(RaycastTemplate, WrongLoopMacrosStopTheCompileSayingWhatToDefine) {
  auto ctx = createHeadlessContext({1, 1});
  // Without the lean loop, the full loop's hand-back would end the ray at its first
  // transparent sample, and the middle loop would have no rounds to run in.
  expectCompileError({"RAY_HAND_BACK 1"},
                     "RAY_HAND_BACK hands the ray back to the lean loop: define RAY_LEAN_LOOP");
  expectCompileError({"RAY_MIDDLE_LOOP 1"},
                     "RAY_MIDDLE_LOOP runs between the lean loop and the full loop: define "
                     "RAY_LEAN_LOOP");
  expectCompileError({"RAY_HAND_BACK 1", "RAY_MIDDLE_LOOP 1"}, "define RAY_LEAN_LOOP");
}

// GlyphShading is one dimension in C++; a program given two shadings by hand (as the three
// bits it was allowed) stops at compile time.
TEST(RaycastTemplate, TwoGlyphShadingsStopTheCompile) {
  auto ctx = createHeadlessContext({1, 1});
  RaycastVariants v;
  v.set(RaycastFeature::Glyphs, 1);
  v.set(RaycastFeature::GlyphShading, static_cast<int>(GlyphShading::Dimples));
  for (const char* second : {"MVW_GLYPH_BOTH 1", "MVW_GLYPH_KINDS 1"})
    expectCompileError({second}, "one glyph shading at most",
                       RaycastPrograms::source(RenderMode::Composite, VolumeLayout::Gradient, v));
}

// A hook the macros call for but the mode does not define: the preprocessor cannot see
// functions, so the GL compiler's own error names it (MIP has no lean-loop hooks).
TEST(RaycastTemplate, AMissingHookIsACompileErrorNamingIt) {
  auto ctx = createHeadlessContext({1, 1});
  expectCompileError({"RAY_LEAN_LOOP 1"}, "leanSample");
}

}  // namespace
}  // namespace mvw::render
