#include "mvw/render/WindowFramebuffer.h"

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
  std::vector<std::uint8_t> rows(image.rgba.size());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // The draw buffer: GL_BACK for a double-buffered window, the only buffer headless.
  GLint drawBuffer = GL_BACK;
  glGetIntegerv(GL_DRAW_BUFFER, &drawBuffer);
  glReadBuffer(static_cast<GLenum>(drawBuffer));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  // GL's row 0 is the bottom one.
  const std::size_t row = static_cast<std::size_t>(size.x) * 4;
  for (int y = 0; y < size.y; ++y)
    std::copy_n(rows.data() + static_cast<std::size_t>(size.y - 1 - y) * row, row,
                image.rgba.data() + static_cast<std::size_t>(y) * row);
  return image;
}

}  // namespace mvw::render
