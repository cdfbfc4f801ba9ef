#pragma once
// An OpenGL 4.5 core context, headless (EGL or OSMesa) or windowed (GLFW), chosen at run
// time. Render code talks to this interface only; the EGL headers stay in EglContext.cpp and
// no OSMesa or GLFW header is included. Every GL function is loaded through the context's
// own GetProcAddress (glad), so one binary can run all of them.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>

namespace mvw::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  virtual void makeCurrent() = 0;
  virtual glm::ivec2 size() const = 0;
  // How the context was made: "egl-device", "egl-surfaceless", "osmesa" (headless) or "glfw".
  virtual std::string backend() const = 0;
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION

 protected:
  GlContext() = default;
  // Loads the GL functions for the current context; throws mvw::Error when that fails.
  static void loadFunctions(void* (*getProcAddress)(const char* name, void* user), void* user);
};

// Which headless GL to use (`--gl`, MVW_GL).
//   auto            EGL (a hardware device, then Mesa's surfaceless platform, then a software
//                   device), then OSMesa
//   egl             the EGL paths of auto only
//   egl-device      EGL_EXT_platform_device only (hardware devices first)
//   egl-surfaceless EGL_MESA_platform_surfaceless only
//   osmesa          OSMesa only
enum class GlRequest { Auto, Egl, EglDevice, EglSurfaceless, OsMesa };
inline constexpr const char* kGlRequestNames = "auto | egl | egl-device | egl-surfaceless | osmesa";
std::optional<GlRequest> parseGlRequest(std::string_view name);
std::string toString(GlRequest request);
// The environment variable that chooses the headless GL where no option does.
inline constexpr const char* kGlEnvironmentVariable = "MVW_GL";
// MVW_GL when set and not empty, else auto. Throws InputError (naming MVW_GL) for an unknown
// value.
GlRequest glRequestFromEnvironment();

// An offscreen GL 4.5 core context of the given size with a default framebuffer of that size,
// current on return, made as `request` says. Throws mvw::Error naming every path tried and
// why each failed (library missing, no device, no core 4.5 context).
std::unique_ptr<GlContext> createHeadlessContext(glm::ivec2 size, GlRequest request);
// The same, as MVW_GL says (auto when unset): what the GL tests use.
std::unique_ptr<GlContext> createHeadlessContext(glm::ivec2 size);

}  // namespace mvw::render
