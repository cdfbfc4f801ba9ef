#include "RenderTarget.h"

#include "ReadPixels.h"

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
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  image.rgba = readRowsTopDown<std::uint8_t>(size_, GL_RGBA, GL_UNSIGNED_BYTE, 4);
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  image.depth = readRowsTopDown<float>(size_, GL_RED, GL_FLOAT, 1);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("rendering");
  return image;
}

}  // namespace mvw::render::detail
