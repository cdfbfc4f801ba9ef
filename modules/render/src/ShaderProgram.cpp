#include "mvw/render/ShaderProgram.h"

#include <utility>

#include <glad/gl.h>

#include "mvw/core/Error.h"
#include "mvw/render/ShaderSource.h"

namespace mvw::render {

namespace {

GLuint compile(GLenum stage, std::string_view path, const std::vector<std::string>& defines,
               const std::vector<std::string>& includes = {}) {
  const ResolvedShader src = resolveShader(path, defines, includes);
  const GLuint shader = glCreateShader(stage);
  const char* text = src.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  glDeleteShader(shader);
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  throw Error("shader compile failed: " + mapShaderLog(log, src.files));
}

}  // namespace

ShaderProgram::ShaderProgram(std::string_view vertexPath, std::string_view fragmentPath,
                             const std::vector<std::string>& defines,
                             const std::vector<std::string>& fragmentIncludes) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertexPath, defines);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragmentPath, defines, fragmentIncludes);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(id_, length, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    throw Error("shader link failed (shaders/" + std::string(vertexPath) + " + shaders/" +
                std::string(fragmentPath) + "): " + log.c_str());
  }
}

ShaderProgram::~ShaderProgram() {
  if (id_) glDeleteProgram(id_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

void ShaderProgram::use() const { glUseProgram(id_); }

int ShaderProgram::uniform(const char* name) const { return glGetUniformLocation(id_, name); }

}  // namespace mvw::render
