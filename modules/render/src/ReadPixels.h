#pragma once
// Reading the bound read buffer back (internal to mvw_render): the one place GL's bottom-up
// rows become an image's top-down ones, for frames, shells and window screenshots.
#include <algorithm>
#include <cstddef>
#include <vector>

#include <glad/gl.h>
#include <glm/vec2.hpp>

namespace mvw::render::detail {

// glReadPixels of `size` pixels of `components` values of type T (format/type as GL names
// them), row 0 the top one.
template <class T>
std::vector<T> readRowsTopDown(glm::ivec2 size, GLenum format, GLenum type, int components) {
  const std::size_t row = static_cast<std::size_t>(size.x) * components;
  std::vector<T> bottomUp(row * size.y), topDown(row * size.y);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.x, size.y, format, type, bottomUp.data());
  for (int y = 0; y < size.y; ++y)
    std::copy_n(bottomUp.data() + static_cast<std::size_t>(size.y - 1 - y) * row, row,
                topDown.data() + static_cast<std::size_t>(y) * row);
  return topDown;
}

}  // namespace mvw::render::detail
