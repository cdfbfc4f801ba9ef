#pragma once
// The windowed GL context: a GLFW window with an OpenGL 4.5 core context whose functions are
// loaded through glfwGetProcAddress into the same loader the renderer uses (render code
// never includes GLFW; this implementation of render::GlContext lives with the viewer).
#include <string>

#include "mvw/render/GlContext.h"

struct GLFWwindow;

namespace mvw::app {

class GlfwContext final : public render::GlContext {
 public:
  // Throws mvw::Error with GLFW's reason when no window or context can be made.
  GlfwContext(glm::ivec2 size, const std::string& title);
  ~GlfwContext() override;
  void makeCurrent() override;
  glm::ivec2 size() const override;  // framebuffer pixels
  std::string backend() const override { return "glfw"; }
  GLFWwindow* window() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace mvw::app
