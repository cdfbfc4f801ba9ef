#pragma once
// An OpenGL 4.5 core context, headless or windowed, chosen at run time. Render code talks
// to this interface only and never includes OSMesa, EGL or GLFW headers; every GL function
// is loaded through the context's own GetProcAddress (glad), so one binary can run both.
#include <memory>
#include <string>

#include <glm/vec2.hpp>

namespace mvw::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  virtual void makeCurrent() = 0;
  virtual glm::ivec2 size() const = 0;
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION

 protected:
  GlContext() = default;
  // Loads the GL functions for the current context; throws mvw::Error when that fails.
  static void loadFunctions(void* (*getProcAddress)(const char* name, void* user), void* user);
};

// An offscreen OSMesa (Mesa llvmpipe) context of the given size, current on return.
// Throws mvw::Error naming the reason (library missing, no core 4.5 context).
std::unique_ptr<GlContext> createHeadlessContext(glm::ivec2 size);

}  // namespace mvw::render
