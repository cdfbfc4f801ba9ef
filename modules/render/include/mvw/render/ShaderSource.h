#pragma once
// GLSL sources come only from shaders/ (embedded at build time). A file may say
// `#include "common/x.glsl"`: each file is pasted once, and `#line L F` directives let
// driver messages be mapped back to shaders/<file>:<line>. Variants are #defines prepended
// here, never string surgery on the source.
#include <string>
#include <string_view>
#include <vector>

namespace mvw::render {

struct ResolvedShader {
  std::string text;                // ready for glShaderSource
  std::vector<std::string> files;  // source-string number F of `#line L F` -> path
};

// `path` after the defines and `includes`: each of those pasted first, in order, as if the file
// began with `#include` lines for them (what a program's variant chooses: RaycastPrograms).
// Throws mvw::Error for an unknown file or include, naming the including file and line.
ResolvedShader resolveShader(std::string_view path, const std::vector<std::string>& defines = {},
                             const std::vector<std::string>& includes = {});

// Rewrites "F:L(C)" (Mesa) and "F(L)" (NVIDIA) locations in a compiler log as
// "shaders/<file>:L:C" / "shaders/<file>:L".
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

// The embedded text of one file (no include resolution); throws mvw::Error if unknown.
std::string_view shaderFile(std::string_view path);

}  // namespace mvw::render
