// Needs a GL context (headless: MVW_GL chooses, auto by default): every program the ray
// caster can make compiles and links, and raycast/template.glsl stops a wrong combination of
// its loop macros at compile time, saying what to define.
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

using detail::RaycastPrograms;
using detail::RaycastSource;
using detail::RaycastVariant;
using detail::RaycastVariants;
using detail::VolumeLayout;

std::string describe(const RaycastSource& s) {
  std::string out = s.vertex + " + " + s.fragment + " with {";
  for (std::size_t i = 0; i < s.defines.size(); ++i) out += (i ? ", " : "") + s.defines[i];
  return out + "}";
}

// One program per mode, layout and combination of variants, compiled and linked as the
// renderer does (ShaderProgram), each named on failure by its files and defines. About 1,600
// programs, mostly composite with glyphs (composite and isosurface each with and without the
// cut face since issue 36): a variant that no view in the golden suite uses breaks here, not in
// a user's first frame.
TEST(RaycastPrograms, EveryProgramCompilesAndLinks) {
  auto ctx = createHeadlessContext({1, 1});
  const std::vector<RaycastSource> every = RaycastPrograms::every();
  int failed = 0;
  for (const RaycastSource& s : every) {
    try {
      ShaderProgram program(s.vertex, s.fragment, s.defines);
    } catch (const Error& e) {
      if (++failed <= 10) ADD_FAILURE() << describe(s) << ": " << e.what();
    }
  }
  RecordProperty("programs", static_cast<int>(every.size()));
  EXPECT_EQ(failed, 0) << "of " << every.size() << " programs";
}

// The enumeration holds each fragment shader forMode uses, and no variant is dead: each one
// changes the defines of some program, so a variant that source() forgets to turn into a
// define shows here.
TEST(RaycastPrograms, EveryVariantAndLayoutReachesADefine) {
  std::vector<std::string> fragments;
  for (const RaycastSource& s : RaycastPrograms::every()) fragments.push_back(s.fragment);
  for (const char* f : {"composite.frag.glsl", "isosurface.frag.glsl", "projection.frag.glsl",
                        "mpr.frag.glsl", "beta.frag.glsl"})
    EXPECT_NE(std::find(fragments.begin(), fragments.end(), f), fragments.end()) << f;
  for (std::size_t bit = 0; bit < RaycastVariants().size(); ++bit) {
    bool changes = false;
    for (const std::string& name : renderModeNames()) {
      const RenderMode mode = *parseRenderMode(name);
      for (int l = 0; l < static_cast<int>(VolumeLayout::Count); ++l) {
        const auto layout = static_cast<VolumeLayout>(l);
        // With every other variant on, so that a variant that needs another (glyph kinds
        // need glyphs) counts.
        RaycastVariants on;
        on.set();
        RaycastVariants off = on;
        off.reset(bit);
        if (RaycastPrograms::source(mode, layout, on).defines !=
            RaycastPrograms::source(mode, layout, off).defines)
          changes = true;
      }
    }
    EXPECT_TRUE(changes) << "variant " << bit << " changes no program's defines";
  }
  for (int l = 1; l < static_cast<int>(VolumeLayout::Count); ++l)
    EXPECT_NE(
        RaycastPrograms::source(RenderMode::Composite, static_cast<VolumeLayout>(l), {}).defines,
        RaycastPrograms::source(RenderMode::Composite, VolumeLayout::Gradient, {}).defines)
        << "layout " << l;
}

// A loop macro set as a mode file would set it, prepended here to MIP's file, whose own loop
// macros (RAY_PREPASS alone) allow it: the compile must fail with the template's message.
void expectCompileError(const std::vector<std::string>& defines, const std::string& message) {
  const RaycastSource s{"box.vert.glsl", "projection.frag.glsl", defines};
  try {
    ShaderProgram program(s.vertex, s.fragment, s.defines);
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
  expectCompileError({"MVW_MIP 1", "RAY_HAND_BACK 1"},
                     "RAY_HAND_BACK hands the ray back to the lean loop: define RAY_LEAN_LOOP");
  expectCompileError({"MVW_MIP 1", "RAY_MIDDLE_LOOP 1"},
                     "RAY_MIDDLE_LOOP runs between the lean loop and the full loop: define "
                     "RAY_LEAN_LOOP");
  expectCompileError({"MVW_MIP 1", "RAY_HAND_BACK 1", "RAY_MIDDLE_LOOP 1"}, "define RAY_LEAN_LOOP");
  // The names before the loop macros got their own prefix: silently ignored, they would run
  // a mode's rays in the full loop alone.
  for (const char* old :
       {"MVW_SPLIT_LOOP 1", "MVW_HAND_BACK 1", "MVW_MIDDLE_LOOP 1", "MVW_PREPASS 1"})
    expectCompileError({"MVW_MINIP 1", old}, "the loop macros are RAY_LEAN_LOOP");
}

// A hook the macros call for but the mode does not define: the preprocessor cannot see
// functions, so the GL compiler's own error names it (MIP has no lean-loop hooks).
TEST(RaycastTemplate, AMissingHookIsACompileErrorNamingIt) {
  auto ctx = createHeadlessContext({1, 1});
  expectCompileError({"MVW_MIP 1", "RAY_LEAN_LOOP 1"}, "leanSample");
}

}  // namespace
}  // namespace mvw::render
