// Needs a GL context (headless: MVW_GL chooses, auto by default): the loader and context layer
// the renderer builds on.
#include <array>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "mvw/core/Error.h"
#include "mvw/render/GlContext.h"

namespace mvw::render {
namespace {

TEST(GlContext, HeadlessCoreContextClearsAndReadsBack) {
  // Intentional odd size: catches row-stride and NPOT mistakes.
  auto ctx = createHeadlessContext({37, 23});
  EXPECT_FALSE(ctx->renderer().empty());
  EXPECT_NE(ctx->version().find("4.5"), std::string::npos) << ctx->version();
  EXPECT_EQ(ctx->size(), glm::ivec2(37, 23));
  glViewport(0, 0, 37, 23);
  glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  std::array<unsigned char, 4> px{};
  glReadPixels(36, 22, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(px[0], 51);
  EXPECT_EQ(px[1], 102);
  EXPECT_EQ(px[2], 153);
  EXPECT_EQ(px[3], 255);
}

TEST(GlContext, ThreeDimensionalTexturesWork) {
  auto ctx = createHeadlessContext({8, 8});
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_3D, tex);
  std::array<unsigned short, 3 * 5 * 7> voxels{};
  for (std::size_t i = 0; i < voxels.size(); ++i) voxels[i] = static_cast<unsigned short>(i * 100);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R16, 3, 5, 7, 0, GL_RED, GL_UNSIGNED_SHORT, voxels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  GLint depth = 0;
  glGetTexLevelParameteriv(GL_TEXTURE_3D, 0, GL_TEXTURE_DEPTH, &depth);
  EXPECT_EQ(depth, 7);
  glDeleteTextures(1, &tex);
}

TEST(GlContext, InvalidSizeIsAnError) { EXPECT_THROW(createHeadlessContext({0, 10}), Error); }

// Every headless path this machine (Debian 12's Mesa) has: OSMesa, EGL surfaceless and EGL's
// software device, each with a default framebuffer of its size that clears and reads back.
TEST(GlContext, EveryHeadlessBackendMakesACoreContextWithADefaultFramebuffer) {
  for (const auto& [request, name] : {std::pair{GlRequest::OsMesa, "osmesa"},
                                      std::pair{GlRequest::EglSurfaceless, "egl-surfaceless"},
                                      std::pair{GlRequest::EglDevice, "egl-device"}}) {
    SCOPED_TRACE(name);
    auto ctx = createHeadlessContext({13, 7}, request);
    EXPECT_EQ(ctx->backend(), name);
    EXPECT_NE(ctx->version().find("4.5"), std::string::npos) << ctx->version();
    glViewport(0, 0, 13, 7);
    glClearColor(1.0f, 0.0f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    std::array<unsigned char, 4> px{};
    glReadPixels(12, 6, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    EXPECT_EQ(px[0], 255);
    EXPECT_EQ(px[1], 0);
    EXPECT_EQ(px[2], 51);
  }
}

// Two contexts on one EGL display at once, the first destroyed first: the display must stay
// usable for the second (no eglTerminate under it).
TEST(GlContext, EglContextsShareTheirDisplay) {
  auto first = createHeadlessContext({4, 4}, GlRequest::EglSurfaceless);
  auto second = createHeadlessContext({5, 5}, GlRequest::EglSurfaceless);
  first.reset();
  second->makeCurrent();
  glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  std::array<unsigned char, 4> px{};
  glReadPixels(4, 4, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  EXPECT_EQ(px[1], 255);
}

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(GlContext, TheEnvironmentChoosesTheHeadlessBackend) {
  {
    ScopedEnv env(kGlEnvironmentVariable, "osmesa");
    EXPECT_EQ(createHeadlessContext({4, 4})->backend(), "osmesa");
  }
  {
    ScopedEnv env(kGlEnvironmentVariable, "egl-surfaceless");
    EXPECT_EQ(createHeadlessContext({4, 4})->backend(), "egl-surfaceless");
  }
  {
    ScopedEnv env(kGlEnvironmentVariable, "");
    EXPECT_EQ(glRequestFromEnvironment(), GlRequest::Auto);
  }
  ScopedEnv env(kGlEnvironmentVariable, "vulkan");
  try {
    createHeadlessContext({4, 4});
    ADD_FAILURE() << "MVW_GL=vulkan was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "MVW_GL");
    EXPECT_NE(e.problem().find("'vulkan'"), std::string::npos) << e.what();
  }
}

TEST(GlContext, RequestNamesRoundTrip) {
  for (GlRequest r : {GlRequest::Auto, GlRequest::Egl, GlRequest::EglDevice,
                      GlRequest::EglSurfaceless, GlRequest::OsMesa})
    EXPECT_EQ(parseGlRequest(toString(r)), r);
  EXPECT_FALSE(parseGlRequest("EGL"));
  EXPECT_FALSE(parseGlRequest(""));
}

}  // namespace
}  // namespace mvw::render

#include "mvw/render/ShaderProgram.h"

namespace mvw::render {
namespace {

TEST(ShaderProgram, EmbeddedProgramDrawsItsColour) {
  auto ctx = createHeadlessContext({31, 17});
  ShaderProgram program("fullscreen.vert.glsl", "solid.frag.glsl");
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glViewport(0, 0, 31, 17);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  program.use();
  glUniform4f(program.uniform("uColor"), 1.5f, 0.5f, 0.25f, 1.0f);  // 1.5 is clamped by the shader
  glDrawArrays(GL_TRIANGLES, 0, 3);
  std::array<unsigned char, 4> px{};
  glReadPixels(15, 8, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  EXPECT_EQ(px[0], 255);
  EXPECT_EQ(px[1], 128);
  EXPECT_EQ(px[2], 64);
  glDeleteVertexArrays(1, &vao);
}

TEST(ShaderProgram, CompileErrorsNameTheShaderFileAndLine) {
  auto ctx = createHeadlessContext({4, 4});
  try {
    // A define that breaks line 5 of solid.frag.glsl ("out vec4 fragColor;"), which comes
    // after the included common/math.glsl: checks that numbering resumes after an include.
    ShaderProgram broken("fullscreen.vert.glsl", "solid.frag.glsl", {"fragColor 1.0 +"});
    ADD_FAILURE() << "compiled a broken shader";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shaders/solid.frag.glsl:5:"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mvw::render
