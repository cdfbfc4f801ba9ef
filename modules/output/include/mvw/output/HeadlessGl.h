#pragma once
// The headless GL context a command renders with, as `--gl` (render, validate, bench) or else
// MVW_GL or else auto chooses it.
#include <memory>
#include <string>

#include <glm/vec2.hpp>

#include "mvw/render/GlContext.h"

namespace mvw::output {

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

}  // namespace mvw::output
