#pragma once
// A linked GL program from two shaders/ files, the defines prepended to both and
// `fragmentIncludes` pasted before the fragment shader's own text (resolveShader). Move-only:
// the GL object is deleted with it.
// Compile and link errors throw mvw::Error with locations mapped to shaders/<file>:<line>.
#include <string>
#include <string_view>
#include <vector>

namespace mvw::render {

class ShaderProgram {
 public:
  ShaderProgram(std::string_view vertexPath, std::string_view fragmentPath,
                const std::vector<std::string>& defines = {},
                const std::vector<std::string>& fragmentIncludes = {});
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;

  unsigned id() const { return id_; }
  void use() const;
  int uniform(const char* name) const;  // -1 if the program does not use it

 private:
  unsigned id_ = 0;
};

}  // namespace mvw::render
