#pragma once
// `--gl auto|egl|egl-device|egl-surfaceless|osmesa` for the subcommands that render headless
// (render, validate, bench): the option wins over MVW_GL, which wins over auto.
#include <memory>
#include <string>

#include <CLI/App.hpp>

#include "mvw/render/GlContext.h"

namespace mvw::app {

void addGlOption(CLI::App& cmd, std::string& gl);
// --gradient auto|texture|shader: where shading takes the anatomy's gradient from
// (render::GradientSource); empty means auto.
void addGradientOption(CLI::App& cmd, std::string& gradient);

// The request the option (empty: not given) and MVW_GL make, and where it came from
// ("--gl egl", "MVW_GL=egl" or "auto"). Throws InputError for an unknown MVW_GL.
struct GlChoice {
  render::GlRequest request = render::GlRequest::Auto;
  std::string origin = "auto";
};
GlChoice resolveGl(const std::string& option);

// A headless context as chosen. A backend the user named that this machine cannot give is
// bad input (InputError naming --gl or MVW_GL, exit 2); auto finding none is an internal
// fault (mvw::Error, exit 1).
std::unique_ptr<render::GlContext> makeHeadlessContext(const std::string& option,
                                                       glm::ivec2 size = {16, 16});

}  // namespace mvw::app
