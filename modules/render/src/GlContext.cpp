#include "mvw/render/GlContext.h"

#include <glad/gl.h>

#include "mvw/core/Error.h"

namespace mvw::render {

namespace {
struct Loader {
  void* (*fn)(const char*, void*);
  void* user;
};
GLADapiproc loadThrough(void* userptr, const char* name) {
  const auto* loader = static_cast<const Loader*>(userptr);
  return reinterpret_cast<GLADapiproc>(loader->fn(name, loader->user));
}
}  // namespace

void GlContext::loadFunctions(void* (*getProcAddress)(const char*, void*), void* user) {
  Loader loader{getProcAddress, user};
  const int version = gladLoadGLUserPtr(loadThrough, &loader);
  if (version == 0) throw Error("cannot load the OpenGL functions of the new context");
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 45)
    throw Error("OpenGL 4.5 core is needed, the context offers " +
                std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                std::to_string(GLAD_VERSION_MINOR(version)));
}

std::string GlContext::renderer() const {
  const auto* s = glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "";
}

std::string GlContext::version() const {
  const auto* s = glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace mvw::render
