#include "TextureUpload.h"

#include <cstdio>
#include <string>

#include "mvw/core/Error.h"

namespace mvw::render::detail {

std::vector<float> valuesOf(const Volume& volume) {
  std::vector<float> out(volume.voxelCount());
  const int nc = volume.components();
  dispatchScalar(volume.scalarType(), [&](auto t) {
    using T = decltype(t);
    const T* p = reinterpret_cast<const T*>(volume.data());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(p[i * nc]);
    return 0;
  });
  return out;
}

void checkGl(const char* what) {
  const GLenum e = glGetError();
  if (e == GL_OUT_OF_MEMORY)
    throw Error(std::string(what) + ": the GL implementation is out of memory for this volume");
  if (e != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "%x", e);
    throw Error(std::string(what) + ": GL error 0x" + code);
  }
}

void setSampling(GLuint texture, GLenum target, bool linear) {
  glBindTexture(target, texture);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
}

Texture upload3D(glm::ivec3 dims, GLint internalFormat, GLenum format, const float* data,
                 bool linear, const char* what) {
  return upload3D(dims, internalFormat, format, GL_FLOAT, data, linear, what);
}

Texture upload3D(glm::ivec3 dims, GLint internalFormat, GLenum format, GLenum type,
                 const void* data, bool linear, const char* what) {
  Texture texture = makeTexture();
  glBindTexture(GL_TEXTURE_3D, texture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, internalFormat, dims.x, dims.y, dims.z, 0, format, type, data);
  checkGl(what);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  setSampling(texture.id(), GL_TEXTURE_3D, linear);
  return texture;
}

glm::dmat4 textureFromIndex(glm::ivec3 dims) {
  glm::dmat4 m(1.0);
  for (int a = 0; a < 3; ++a) {
    m[a][a] = 1.0 / dims[a];
    m[3][a] = 0.5 / dims[a];
  }
  return m;
}

void uploadColorTable(GLuint texture, const ColorTable& table) {
  std::vector<std::uint8_t> rgba(256 * 4, 255);
  for (std::size_t i = 0; i < 256; ++i)
    for (std::size_t c = 0; c < 3; ++c) rgba[4 * i + c] = table.rgb[i][c];
  glBindTexture(GL_TEXTURE_1D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, 256, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAX_LEVEL, 0);
  checkGl("uploading a colour map");
}

}  // namespace mvw::render::detail
