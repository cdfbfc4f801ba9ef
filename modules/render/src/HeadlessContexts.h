#pragma once
// The headless GL implementations behind createHeadlessContext (GlContext.cpp chooses).
#include <memory>

#include <glm/vec2.hpp>

#include "mvw/render/GlContext.h"

namespace mvw::render::detail {

// Throws Error for a size no headless context takes.
void checkHeadlessSize(glm::ivec2 size);

// Each throws Error saying why it cannot make a context.
std::unique_ptr<GlContext> createOsMesaContext(glm::ivec2 size);

enum class EglPlatform {
  HardwareDevice,  // EGL_EXT_platform_device, a device without EGL_MESA_device_software
  SoftwareDevice,  // EGL_EXT_platform_device, Mesa's software (llvmpipe) device
  Surfaceless,     // EGL_MESA_platform_surfaceless
};
std::unique_ptr<GlContext> createEglContext(glm::ivec2 size, EglPlatform platform);

}  // namespace mvw::render::detail
