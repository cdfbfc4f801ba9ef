#pragma once
// Move-only owners of GL objects (internal to mvw_render): copy deleted, noexcept move,
// glDelete* in the destructor. Need a current context for their whole life.
#include <utility>

#include <glad/gl.h>

namespace mvw::render::detail {

template <void (*Delete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  ~GlName() {
    if (id_) Delete(id_);
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GlName(GlName&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlName& operator=(GlName&& o) noexcept {
    if (this != &o) {
      if (id_) Delete(id_);
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

inline void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }

using Texture = GlName<deleteTexture>;
using Framebuffer = GlName<deleteFramebuffer>;
using VertexArray = GlName<deleteVertexArray>;
using Buffer = GlName<deleteBuffer>;

inline Texture makeTexture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return Texture(id);
}
inline Framebuffer makeFramebuffer() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  return Framebuffer(id);
}
inline VertexArray makeVertexArray() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  return VertexArray(id);
}
inline Buffer makeBuffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  return Buffer(id);
}

}  // namespace mvw::render::detail
