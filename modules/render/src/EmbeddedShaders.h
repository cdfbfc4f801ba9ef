#pragma once
#include <map>
#include <string_view>

namespace mvw::render::detail {

// Every shaders/**/*.glsl, keyed by its path relative to shaders/ (generated at build time by
// cmake/EmbedFiles.cmake).
const std::map<std::string_view, std::string_view>& embeddedShaders();

}  // namespace mvw::render::detail
