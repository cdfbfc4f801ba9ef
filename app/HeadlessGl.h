#pragma once
// `--gl auto|egl|egl-device|egl-surfaceless|osmesa` for the subcommands that render headless
// (render, validate, bench): the option wins over MVW_GL, which wins over auto
// (output::makeHeadlessContext).
#include <string>

#include <CLI/App.hpp>

#include "mvw/render/GlContext.h"

namespace mvw::app {

void addGlOption(CLI::App& cmd, std::string& gl);
// --gradient auto|texture|shader: where shading takes the anatomy's gradient from
// (render::GradientSource); empty means auto.
void addGradientOption(CLI::App& cmd, std::string& gradient);

}  // namespace mvw::app
