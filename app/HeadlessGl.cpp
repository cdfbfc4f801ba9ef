#include "HeadlessGl.h"

#include <CLI/CLI.hpp>

#include "mvw/core/Error.h"

namespace mvw::app {

void addGlOption(CLI::App& cmd, std::string& gl) {
  cmd.add_option("--gl", gl,
                 std::string("Headless GL: ") + render::kGlRequestNames +
                     " (default: $MVW_GL, else auto: an EGL GPU device, Mesa's EGL surfaceless "
                     "platform, Mesa's EGL software device, OSMesa)")
      ->check(CLI::IsMember({"auto", "egl", "egl-device", "egl-surfaceless", "osmesa"}));
}

void addGradientOption(CLI::App& cmd, std::string& gradient) {
  cmd.add_option("--gradient", gradient,
                 "Shading gradient: texture (precomputed, 8 bytes a voxel), shader (on the fly, "
                 "no memory) or auto (the texture up to 512 MiB of it; default)")
      ->check(CLI::IsMember({"auto", "texture", "shader"}));
}

GlChoice resolveGl(const std::string& option) {
  if (!option.empty()) return {*render::parseGlRequest(option), "--gl " + option};
  const render::GlRequest request = render::glRequestFromEnvironment();
  if (request == render::GlRequest::Auto) return {};
  return {request, std::string(render::kGlEnvironmentVariable) + "=" + render::toString(request)};
}

std::unique_ptr<render::GlContext> makeHeadlessContext(const std::string& option, glm::ivec2 size) {
  const GlChoice choice = resolveGl(option);
  try {
    return render::createHeadlessContext(size, choice.request);
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    if (choice.request == render::GlRequest::Auto) throw;
    throw InputError(choice.origin, e.what());
  }
}

}  // namespace mvw::app
