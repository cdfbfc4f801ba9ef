#pragma once
// A rendered frame: RGBA8 pixels, top row first (as PNG stores them), plus an optional
// float channel per pixel (the ray distance in mm of the first hit or of the maximum).
#include <cstdint>
#include <vector>

namespace mvw {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4, row 0 = top
  std::vector<float> depth;        // width * height, or empty; row 0 = top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0) {}
  std::uint8_t* pixel(int x, int y) {
    return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
  const std::uint8_t* pixel(int x, int y) const {
    return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
};

}  // namespace mvw
