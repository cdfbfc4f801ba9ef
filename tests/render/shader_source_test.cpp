// The shader include resolver and log mapping, without a GL context.
#include <gtest/gtest.h>

#include "mvw/core/Error.h"
#include "mvw/render/ShaderSource.h"

namespace mvw::render {
namespace {

TEST(ShaderSource, ResolvesIncludesOnceWithLineDirectives) {
  const ResolvedShader s = resolveShader("solid.frag.glsl", {"MVW_TEST 1"});
  ASSERT_EQ(s.files.size(), 2u);
  EXPECT_EQ(s.files[0], "solid.frag.glsl");
  EXPECT_EQ(s.files[1], "common/math.glsl");
  EXPECT_EQ(s.text.rfind("#version 450 core\n#define MVW_TEST 1\n#line 1 0\n", 0), 0u) << s.text;
  EXPECT_NE(s.text.find("#line 1 1\n"), std::string::npos);
  EXPECT_NE(s.text.find("float mvwSaturate"), std::string::npos);
  EXPECT_EQ(s.text.find("#include"), std::string::npos);
  // After the include (line 2 of solid.frag.glsl) numbering resumes at line 3 of file 0.
  EXPECT_NE(s.text.find("#line 3 0\n"), std::string::npos);
}

// A program's variant pastes files before the shader's own (RaycastPrograms): each once, in
// order, after the defines, and an include the shader also names is not pasted again.
TEST(ShaderSource, PastesTheGivenIncludesFirstAndEachOnce) {
  const ResolvedShader s = resolveShader("solid.frag.glsl", {"MVW_TEST 1"},
                                         {"common/math.glsl", "common/colormap.glsl"});
  ASSERT_EQ(s.files.size(), 3u);
  EXPECT_EQ(s.files[0], "common/math.glsl");
  EXPECT_EQ(s.files[1], "common/colormap.glsl");
  EXPECT_EQ(s.files[2], "solid.frag.glsl");
  EXPECT_EQ(s.text.rfind("#version 450 core\n#define MVW_TEST 1\n#line 1 0\n", 0), 0u) << s.text;
  EXPECT_EQ(s.text.find("float mvwSaturate"), s.text.rfind("float mvwSaturate"));
  EXPECT_LT(s.text.find("uImageColormap"), s.text.find("#line 1 2\n"));
  EXPECT_THROW(resolveShader("solid.frag.glsl", {}, {"no-such.glsl"}), Error);
}

TEST(ShaderSource, MapsMesaAndNvidiaLocationsToFiles) {
  const std::vector<std::string> files = {"a.frag.glsl", "common/math.glsl"};
  EXPECT_EQ(mapShaderLog("1:7(12): error: syntax error", files),
            "shaders/common/math.glsl:7:12: error: syntax error");
  EXPECT_EQ(mapShaderLog("0(3) : error C0000: bad", files),
            "shaders/a.frag.glsl:3 : error C0000: bad");
  EXPECT_EQ(mapShaderLog("9:1(1): unknown file", files), "9:1(1): unknown file");
}

TEST(ShaderSource, UnknownFileIsAnError) { EXPECT_THROW(resolveShader("no-such.glsl"), Error); }

}  // namespace
}  // namespace mvw::render
