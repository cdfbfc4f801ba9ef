#include "mvw/render/WindowFramebuffer.h"

#include "ReadPixels.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glad/gl.h>

namespace mvw::render {

void WindowFramebuffer::clear(const glm::vec4& colour) {
  const glm::ivec2 size = context_->size();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, size.x, size.y);
  glClearColor(colour.r, colour.g, colour.b, colour.a);
  glClear(GL_COLOR_BUFFER_BIT);
}

Image WindowFramebuffer::read() const {
  const glm::ivec2 size = context_->size();
  Image image(size.x, size.y);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // The draw buffer: GL_BACK for a double-buffered window, the only buffer headless.
  GLint drawBuffer = GL_BACK;
  glGetIntegerv(GL_DRAW_BUFFER, &drawBuffer);
  glReadBuffer(static_cast<GLenum>(drawBuffer));
  image.rgba = detail::readRowsTopDown<std::uint8_t>(size, GL_RGBA, GL_UNSIGNED_BYTE, 4);
  return image;
}

}  // namespace mvw::render
