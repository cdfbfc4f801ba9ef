#include "RenderTarget.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "TextureUpload.h"
#include "mvw/core/Error.h"

namespace mvw::render::detail {

void RenderTarget::bind(glm::ivec2 size) {
  if (framebuffer_.id() && size == size_) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    return;
  }
  // Forget the old target first: a failure below must not leave one of the wrong size cached.
  framebuffer_ = Framebuffer();
  size_ = size;
  colour_ = makeTexture();
  depth_ = makeTexture();
  glBindTexture(GL_TEXTURE_2D, colour_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, size.x, size.y, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glBindTexture(GL_TEXTURE_2D, depth_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, size.x, size.y, 0, GL_RED, GL_FLOAT, nullptr);
  Framebuffer framebuffer = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_.id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, depth_.id(), 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, buffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw Error("render target of " + std::to_string(size.x) + " x " + std::to_string(size.y) +
                " is not supported");
  }
  checkGl("creating the render target");
  framebuffer_ = std::move(framebuffer);
}

Image RenderTarget::read() const {
  Image image(size_.x, size_.y);
  image.depth.resize(static_cast<std::size_t>(size_.x) * size_.y);
  std::vector<std::uint8_t> rgba(image.rgba.size());
  std::vector<float> depth(image.depth.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, size_.x, size_.y, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glReadPixels(0, 0, size_.x, size_.y, GL_RED, GL_FLOAT, depth.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("rendering");
  // GL rows start at the bottom; images at the top.
  const std::size_t row = static_cast<std::size_t>(size_.x) * 4;
  for (int y = 0; y < size_.y; ++y) {
    std::copy_n(rgba.data() + (size_.y - 1 - y) * row, row, image.rgba.data() + y * row);
    std::copy_n(depth.data() + static_cast<std::size_t>(size_.y - 1 - y) * size_.x, size_.x,
                image.depth.data() + static_cast<std::size_t>(y) * size_.x);
  }
  return image;
}

}  // namespace mvw::render::detail
