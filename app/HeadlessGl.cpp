#include "HeadlessGl.h"

#include <CLI/CLI.hpp>

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

}  // namespace mvw::app
