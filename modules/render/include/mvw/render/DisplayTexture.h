#pragma once
// A rendered image on the GPU for a window to draw (the viewer's panes, drawn by Dear ImGui's
// OpenGL backend): a 2D RGBA8 texture with linear filtering. Move-only; the GL object exists
// from the first upload and needs the same context current until it is destroyed. The GL
// loader stays private to mvw_render, so code that only shows images never calls GL.
#include <cstdint>

#include <glm/vec2.hpp>

#include "mvw/core/Image.h"

namespace mvw::render {

class DisplayTexture {
 public:
  DisplayTexture() = default;  // no GL object yet: safe to make before a context exists
  ~DisplayTexture();
  DisplayTexture(const DisplayTexture&) = delete;
  DisplayTexture& operator=(const DisplayTexture&) = delete;
  DisplayTexture(DisplayTexture&& other) noexcept;
  DisplayTexture& operator=(DisplayTexture&& other) noexcept;

  // Replaces the contents with `image` (row 0 at texture coordinate v = 0, so a quad drawn
  // with v = 0 at its top shows it upright, as ImGui draws images).
  void upload(const Image& image);
  bool empty() const { return name_ == 0; }
  glm::ivec2 size() const { return size_; }
  // The GL texture name as a pointer-sized handle: what ImGui's OpenGL3 backend takes as its
  // ImTextureID.
  std::uintptr_t handle() const { return name_; }

 private:
  unsigned int name_ = 0;  // a GLuint
  glm::ivec2 size_{0};
};

}  // namespace mvw::render
