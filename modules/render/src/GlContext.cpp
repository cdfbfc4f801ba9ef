#include "mvw/render/GlContext.h"

#include <cstdlib>
#include <utility>
#include <vector>

#include <glad/gl.h>

#include "HeadlessContexts.h"
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

std::optional<GlRequest> parseGlRequest(std::string_view name) {
  if (name == "auto") return GlRequest::Auto;
  if (name == "egl") return GlRequest::Egl;
  if (name == "egl-device") return GlRequest::EglDevice;
  if (name == "egl-surfaceless") return GlRequest::EglSurfaceless;
  if (name == "osmesa") return GlRequest::OsMesa;
  return std::nullopt;
}

std::string toString(GlRequest request) {
  switch (request) {
    case GlRequest::Auto:
      return "auto";
    case GlRequest::Egl:
      return "egl";
    case GlRequest::EglDevice:
      return "egl-device";
    case GlRequest::EglSurfaceless:
      return "egl-surfaceless";
    case GlRequest::OsMesa:
      return "osmesa";
  }
  return "auto";
}

GlRequest glRequestFromEnvironment() {
  const char* value = std::getenv(kGlEnvironmentVariable);
  if (!value || !*value) return GlRequest::Auto;
  if (const auto request = parseGlRequest(value)) return *request;
  throw InputError(kGlEnvironmentVariable, std::string("unknown headless GL '") + value +
                                               "' (expected " + kGlRequestNames + ")");
}

void detail::checkHeadlessSize(glm::ivec2 size) {
  if (size.x <= 0 || size.y <= 0 || size.x > 16384 || size.y > 16384)
    throw Error("headless GL context: invalid size " + std::to_string(size.x) + " x " +
                std::to_string(size.y));
}

std::unique_ptr<GlContext> createHeadlessContext(glm::ivec2 size, GlRequest request) {
  detail::checkHeadlessSize(size);
  using detail::EglPlatform;
  struct Path {
    const char* name;
    std::unique_ptr<GlContext> (*create)(glm::ivec2);
  };
  const Path hardware{"egl-device (hardware)", [](glm::ivec2 s) {
                        return detail::createEglContext(s, EglPlatform::HardwareDevice);
                      }};
  const Path surfaceless{"egl-surfaceless", [](glm::ivec2 s) {
                           return detail::createEglContext(s, EglPlatform::Surfaceless);
                         }};
  const Path software{"egl-device (software)", [](glm::ivec2 s) {
                        return detail::createEglContext(s, EglPlatform::SoftwareDevice);
                      }};
  const Path osmesa{"osmesa", detail::createOsMesaContext};
  // A GPU first; Mesa's surfaceless platform before its software device, since both are
  // llvmpipe and surfaceless is the one every Mesa build has.
  std::vector<Path> paths;
  switch (request) {
    case GlRequest::Auto:
      paths = {hardware, surfaceless, software, osmesa};
      break;
    case GlRequest::Egl:
      paths = {hardware, surfaceless, software};
      break;
    case GlRequest::EglDevice:
      paths = {hardware, software};
      break;
    case GlRequest::EglSurfaceless:
      paths = {surfaceless};
      break;
    case GlRequest::OsMesa:
      paths = {osmesa};
      break;
  }
  std::string reasons;
  for (const Path& path : paths) {
    try {
      return path.create(size);
    } catch (const Error& e) {
      reasons += std::string(reasons.empty() ? "" : "; ") + path.name + ": " + e.what();
    }
  }
  throw Error("cannot make a headless OpenGL 4.5 core context: " + reasons);
}

std::unique_ptr<GlContext> createHeadlessContext(glm::ivec2 size) {
  return createHeadlessContext(size, glRequestFromEnvironment());
}

}  // namespace mvw::render
