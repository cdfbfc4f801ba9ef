#include "mvw/render/DisplayTexture.h"

#include <type_traits>
#include <utility>

#include <glad/gl.h>

namespace mvw::render {

static_assert(std::is_same_v<GLuint, unsigned int>, "DisplayTexture keeps a GLuint");

DisplayTexture::~DisplayTexture() {
  if (name_) glDeleteTextures(1, &name_);
}

DisplayTexture::DisplayTexture(DisplayTexture&& other) noexcept
    : name_(std::exchange(other.name_, 0)), size_(std::exchange(other.size_, glm::ivec2(0))) {}

DisplayTexture& DisplayTexture::operator=(DisplayTexture&& other) noexcept {
  if (this != &other) {
    if (name_) glDeleteTextures(1, &name_);
    name_ = std::exchange(other.name_, 0);
    size_ = std::exchange(other.size_, glm::ivec2(0));
  }
  return *this;
}

void DisplayTexture::upload(const Image& image) {
  if (!name_) glGenTextures(1, &name_);
  glBindTexture(GL_TEXTURE_2D, name_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of odd widths are tightly packed
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               image.rgba.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  size_ = {image.width, image.height};
}

}  // namespace mvw::render
