// Headless GL through OSMesa, opened with dlopen: libOSMesa exports its own gl* symbols,
// which would clash with libGL's in a binary that also opens a window, so nothing links it.
#include <dlfcn.h>

#include <vector>

#include <glad/gl.h>

#include "HeadlessContexts.h"
#include "mvw/core/Error.h"
#include "mvw/render/GlContext.h"

namespace mvw::render {

namespace {

// From GL/osmesa.h (Mesa), repeated here so render code includes no OSMesa header.
constexpr int kOsmesaRgba = 0x1908;
constexpr int kOsmesaFormat = 0x22;
constexpr int kOsmesaDepthBits = 0x30;
constexpr int kOsmesaStencilBits = 0x31;
constexpr int kOsmesaProfile = 0x33;
constexpr int kOsmesaCoreProfile = 0x34;
constexpr int kOsmesaMajor = 0x36;
constexpr int kOsmesaMinor = 0x37;

using OSMesaContextHandle = void*;
using CreateFn = OSMesaContextHandle (*)(const int*, OSMesaContextHandle);
using MakeCurrentFn = unsigned char (*)(OSMesaContextHandle, void*, unsigned int, int, int);
using DestroyFn = void (*)(OSMesaContextHandle);
using GetProcFn = void* (*)(const char*);

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(glm::ivec2 size)
      : size_(size), pixels_(static_cast<std::size_t>(size.x) * size.y * 4) {
    detail::checkHeadlessSize(size);
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"}) {
      lib_ = ::dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (lib_) break;
    }
    if (!lib_)
      throw Error("cannot open libOSMesa.so.8 (install libosmesa6): " + std::string(::dlerror()));
    auto create = reinterpret_cast<CreateFn>(::dlsym(lib_, "OSMesaCreateContextAttribs"));
    makeCurrent_ = reinterpret_cast<MakeCurrentFn>(::dlsym(lib_, "OSMesaMakeCurrent"));
    destroy_ = reinterpret_cast<DestroyFn>(::dlsym(lib_, "OSMesaDestroyContext"));
    getProc_ = reinterpret_cast<GetProcFn>(::dlsym(lib_, "OSMesaGetProcAddress"));
    if (!create || !makeCurrent_ || !destroy_ || !getProc_) {
      throw Error("libOSMesa lacks OSMesaCreateContextAttribs (Mesa too old)");
    }
    const int attribs[] = {kOsmesaFormat,
                           kOsmesaRgba,
                           kOsmesaDepthBits,
                           24,
                           kOsmesaStencilBits,
                           8,
                           kOsmesaProfile,
                           kOsmesaCoreProfile,
                           kOsmesaMajor,
                           4,
                           kOsmesaMinor,
                           5,
                           0};
    context_ = create(attribs, nullptr);
    if (!context_) {
      throw Error("OSMesa could not create an OpenGL 4.5 core context");
    }
    makeCurrent();
    loadFunctions([](const char* name,
                     void* self) { return static_cast<OsMesaContext*>(self)->getProc_(name); },
                  this);
  }

  // The library stays loaded: Mesa and its LLVM keep process-wide state that does not
  // survive being unloaded and reloaded by the next context.
  ~OsMesaContext() override { destroy_(context_); }

  void makeCurrent() override {
    // GL_UNSIGNED_BYTE = 0x1401: the colour buffer is pixels_, RGBA8, bottom row first.
    if (!makeCurrent_(context_, pixels_.data(), 0x1401, size_.x, size_.y))
      throw Error("headless GL: OSMesaMakeCurrent failed");
  }

  glm::ivec2 size() const override { return size_; }
  std::string backend() const override { return "osmesa"; }

 private:
  glm::ivec2 size_;
  std::vector<unsigned char> pixels_;
  void* lib_ = nullptr;
  OSMesaContextHandle context_ = nullptr;
  MakeCurrentFn makeCurrent_ = nullptr;
  DestroyFn destroy_ = nullptr;
  GetProcFn getProc_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> detail::createOsMesaContext(glm::ivec2 size) {
  return std::make_unique<OsMesaContext>(size);
}

}  // namespace mvw::render
