// Headless GL through EGL: a GPU through EGL_EXT_platform_device (a server without X), or
// Mesa's llvmpipe through EGL_MESA_platform_surfaceless or its software device. libEGL
// (glvnd) is opened with dlopen, as OSMesa is, so a machine without it still falls back to
// OSMesa, and no target links it. The context is desktop GL 4.5 core (eglBindAPI
// EGL_OPENGL_API), the same shaders as OSMesa and the window.
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// Only the types and constants: every function comes from dlsym / eglGetProcAddress.
// EGL_NO_X11: no Xlib headers (their macros clash), the headless platforms need none.
#define EGL_EGL_PROTOTYPES 0
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "HeadlessContexts.h"
#include "mvw/core/Error.h"
#include "mvw/render/GlContext.h"

namespace mvw::render {

namespace {

std::string hex(EGLint code) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04x", static_cast<unsigned>(code));
  return b;
}

bool hasExtension(const char* list, const std::string& name) {
  if (!list) return false;
  const std::string s = std::string(" ") + list + " ";
  return s.find(" " + name + " ") != std::string::npos;
}

// libEGL's entry points, loaded once per process. The library stays loaded, as OSMesa does.
struct Egl {
  PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
  PFNEGLGETERRORPROC getError = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLQUERYSTRINGPROC queryString = nullptr;
  PFNEGLBINDAPIPROC bindApi = nullptr;
  PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC createContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
  PFNEGLCREATEPBUFFERSURFACEPROC createPbufferSurface = nullptr;
  PFNEGLDESTROYSURFACEPROC destroySurface = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
  PFNEGLGETCURRENTCONTEXTPROC getCurrentContext = nullptr;
  // Client extensions (may stay null).
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
  std::string clientExtensions;
  std::string loadError;  // empty when loaded

  std::string lastError() const { return hex(getError()); }
};

const Egl& egl() {
  static const Egl instance = [] {
    Egl e;
    void* lib = nullptr;
    for (const char* name : {"libEGL.so.1", "libEGL.so"}) {
      lib = ::dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (lib) break;
    }
    if (!lib) {
      e.loadError = "cannot open libEGL.so.1 (install libegl1): " + std::string(::dlerror());
      return e;
    }
    auto load = [lib](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(::dlsym(lib, name));
      return fn != nullptr;
    };
    if (!load(e.getProcAddress, "eglGetProcAddress") || !load(e.getError, "eglGetError") ||
        !load(e.initialize, "eglInitialize") || !load(e.queryString, "eglQueryString") ||
        !load(e.bindApi, "eglBindAPI") || !load(e.chooseConfig, "eglChooseConfig") ||
        !load(e.createContext, "eglCreateContext") ||
        !load(e.destroyContext, "eglDestroyContext") ||
        !load(e.createPbufferSurface, "eglCreatePbufferSurface") ||
        !load(e.destroySurface, "eglDestroySurface") || !load(e.makeCurrent, "eglMakeCurrent") ||
        !load(e.getCurrentContext, "eglGetCurrentContext")) {
      e.loadError = "libEGL lacks an EGL 1.4 entry point";
      return e;
    }
    // EGL_NO_DISPLAY: the client extensions (EGL_EXT_client_extensions).
    const char* client = e.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    e.getError();  // an EGL without client extensions sets EGL_BAD_DISPLAY here
    e.clientExtensions = client ? client : "";
    auto ext = [&e](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(e.getProcAddress(name));
    };
    if (hasExtension(client, "EGL_EXT_platform_base"))
      ext(e.getPlatformDisplay, "eglGetPlatformDisplayEXT");
    if (hasExtension(client, "EGL_EXT_device_enumeration") ||
        hasExtension(client, "EGL_EXT_device_base"))
      ext(e.queryDevices, "eglQueryDevicesEXT");
    if (hasExtension(client, "EGL_EXT_device_query") || hasExtension(client, "EGL_EXT_device_base"))
      ext(e.queryDeviceString, "eglQueryDeviceStringEXT");
    return e;
  }();
  if (!instance.loadError.empty()) throw Error(instance.loadError);
  return instance;
}

class EglContext final : public GlContext {
 public:
  // `display` is initialised; it stays so for the process (an EGLDisplay is shared by every
  // context on it, and eglTerminate would pull it from under another one).
  EglContext(EGLDisplay display, glm::ivec2 size, std::string backend)
      : display_(display), size_(size), backend_(std::move(backend)) {
    const Egl& e = egl();
    if (!e.bindApi(EGL_OPENGL_API))
      throw Error("eglBindAPI(EGL_OPENGL_API) failed (" + e.lastError() + "): no desktop GL");
    // A pbuffer of the context's size gives the same default framebuffer as OSMesa's
    // (tests and WindowFramebuffer draw there); the renderer itself draws into its own FBO.
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                    EGL_PBUFFER_BIT,
                                    EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT,
                                    EGL_RED_SIZE,
                                    8,
                                    EGL_GREEN_SIZE,
                                    8,
                                    EGL_BLUE_SIZE,
                                    8,
                                    EGL_ALPHA_SIZE,
                                    8,
                                    EGL_DEPTH_SIZE,
                                    24,
                                    EGL_STENCIL_SIZE,
                                    8,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    // MVW_EGL_NO_PBUFFER=1 takes the surfaceless-context path below on a display that has
    // pbuffers too, so that path is tested (tests/render/gl-backends).
    const char* noPbuffer = std::getenv("MVW_EGL_NO_PBUFFER");
    if ((noPbuffer && *noPbuffer && std::string(noPbuffer) != "0") ||
        !e.chooseConfig(display_, configAttribs, &config, 1, &configs))
      configs = 0;
    const char* extensions = e.queryString(display_, EGL_EXTENSIONS);
    if (configs == 0) {
      // No pbuffer config: a context without a default framebuffer (the renderer's FBOs
      // still work), where the display allows one.
      if (!hasExtension(extensions, "EGL_KHR_surfaceless_context") ||
          !hasExtension(extensions, "EGL_KHR_no_config_context"))
        throw Error("no RGBA8 pbuffer config with desktop GL and no EGL_KHR_surfaceless_context");
      config = EGL_NO_CONFIG_KHR;
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    context_ = e.createContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT)
      throw Error("cannot create an OpenGL 4.5 core context (" + e.lastError() + ")");
    try {
      if (configs > 0) {
        const EGLint surfaceAttribs[] = {EGL_WIDTH, size.x, EGL_HEIGHT, size.y, EGL_NONE};
        surface_ = e.createPbufferSurface(display_, config, surfaceAttribs);
        if (surface_ == EGL_NO_SURFACE)
          throw Error("cannot create a " + std::to_string(size.x) + " x " + std::to_string(size.y) +
                      " pbuffer (" + e.lastError() + ")");
      }
      makeCurrent();
      loadFunctions([](const char* name,
                       void*) { return reinterpret_cast<void*>(egl().getProcAddress(name)); },
                    nullptr);
    } catch (...) {
      release();
      throw;
    }
  }

  ~EglContext() override { release(); }

  void makeCurrent() override {
    const Egl& e = egl();
    if (!e.makeCurrent(display_, surface_, surface_, context_))
      throw Error("headless GL: eglMakeCurrent failed (" + e.lastError() + ")");
  }

  glm::ivec2 size() const override { return size_; }
  std::string backend() const override { return backend_; }

 private:
  void release() noexcept {
    const Egl& e = egl();
    if (context_ != EGL_NO_CONTEXT && e.getCurrentContext() == context_)
      e.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) e.destroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) e.destroyContext(display_, context_);
    surface_ = EGL_NO_SURFACE;
    context_ = EGL_NO_CONTEXT;
  }

  EGLDisplay display_;
  glm::ivec2 size_;
  std::string backend_;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
};

EGLDisplay initialise(EGLDisplay display, const std::string& what) {
  const Egl& e = egl();
  if (display == EGL_NO_DISPLAY)
    throw Error("no EGL display for " + what + " (" + e.lastError() + ")");
  EGLint major = 0, minor = 0;
  if (!e.initialize(display, &major, &minor))
    throw Error("eglInitialize failed for " + what + " (" + e.lastError() + ")");
  if (major * 10 + minor < 15 &&
      !hasExtension(e.queryString(display, EGL_EXTENSIONS), "EGL_KHR_create_context"))
    throw Error(what + " offers EGL " + std::to_string(major) + "." + std::to_string(minor) +
                " without EGL_KHR_create_context: no core profile");
  return display;
}

std::unique_ptr<GlContext> surfacelessContext(glm::ivec2 size) {
  const Egl& e = egl();
  if (!hasExtension(e.clientExtensions.c_str(), "EGL_MESA_platform_surfaceless") ||
      !e.getPlatformDisplay)
    throw Error("libEGL offers no EGL_MESA_platform_surfaceless (no Mesa EGL vendor)");
  const EGLDisplay display =
      initialise(e.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                 "Mesa's surfaceless platform");
  return std::make_unique<EglContext>(display, size, "egl-surfaceless");
}

std::unique_ptr<GlContext> deviceContext(glm::ivec2 size, bool software) {
  const Egl& e = egl();
  if (!hasExtension(e.clientExtensions.c_str(), "EGL_EXT_platform_device") ||
      !e.getPlatformDisplay || !e.queryDevices || !e.queryDeviceString)
    throw Error("libEGL offers no EGL_EXT_platform_device with EGL_EXT_device_enumeration");
  EGLint count = 0;
  if (!e.queryDevices(0, nullptr, &count) || count <= 0)
    throw Error("eglQueryDevicesEXT finds no EGL device");
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (!e.queryDevices(count, devices.data(), &count))
    throw Error("eglQueryDevicesEXT failed (" + e.lastError() + ")");
  devices.resize(static_cast<std::size_t>(count));
  std::string reasons;
  int tried = 0;
  for (int i = 0; i < count; ++i) {
    const char* ext = e.queryDeviceString(devices[static_cast<std::size_t>(i)], EGL_EXTENSIONS);
    if (hasExtension(ext, "EGL_MESA_device_software") != software) continue;
    ++tried;
    const std::string what = "EGL device " + std::to_string(i);
    try {
      const EGLDisplay display =
          initialise(e.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT,
                                          devices[static_cast<std::size_t>(i)], nullptr),
                     what);
      return std::make_unique<EglContext>(display, size, "egl-device");
    } catch (const Error& err) {
      reasons += std::string(reasons.empty() ? "" : "; ") + err.what();
    }
  }
  if (tried == 0)
    throw Error("no " + std::string(software ? "software" : "hardware") + " EGL device among " +
                std::to_string(count));
  throw Error(reasons);
}

}  // namespace

std::unique_ptr<GlContext> detail::createEglContext(glm::ivec2 size, EglPlatform platform) {
  switch (platform) {
    case EglPlatform::HardwareDevice:
      return deviceContext(size, false);
    case EglPlatform::SoftwareDevice:
      return deviceContext(size, true);
    case EglPlatform::Surfaceless:
      return surfacelessContext(size);
  }
  throw Error("unknown EGL platform");
}

}  // namespace mvw::render
