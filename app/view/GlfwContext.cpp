#include "GlfwContext.h"

#include <dlfcn.h>

#include <GLFW/glfw3.h>

#include "mvw/core/Error.h"

namespace mvw::app {

namespace {
std::string glfwReason() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? text : "unknown reason";
}
}  // namespace

GlfwContext::GlfwContext(glm::ivec2 size, const std::string& title) {
  // Mesa's GL libraries and DRI driver stay loaded after glfwTerminate (RTLD_NODELETE):
  // unloading swrast_dri.so at exit orphaned its global allocations, which LeakSanitizer then
  // reported from an unknown module. (A library missing here is simply not pinned.)
  for (const char* lib :
       {"libGL.so.1", "libGLX_mesa.so.0", "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so"})
    ::dlopen(lib, RTLD_LAZY | RTLD_NODELETE);
  if (!glfwInit())
    throw InputError("mvw view",
                     "cannot open a window: no display (set DISPLAY, or run under Xvfb; mvw "
                     "render draws the same views headless): " +
                         glfwReason());
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(size.x, size.y, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string reason = glfwReason();
    glfwTerminate();
    throw Error("cannot open an OpenGL 4.5 core window: " + reason);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
  loadFunctions(
      [](const char* name, void*) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); },
      nullptr);
}

GlfwContext::~GlfwContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void GlfwContext::makeCurrent() { glfwMakeContextCurrent(window_); }

glm::ivec2 GlfwContext::size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

}  // namespace mvw::app
