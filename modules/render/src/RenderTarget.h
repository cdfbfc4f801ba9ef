#pragma once
// The ray caster's framebuffer (internal to mvw_render): RGBA8 colour and the R32F ray depth,
// kept between frames and recreated only when the size changes, since an interactive view
// renders the same size over and over.
#include <glm/vec2.hpp>

#include "GlObjects.h"
#include "mvw/core/Image.h"

namespace mvw::render::detail {

class RenderTarget {
 public:
  // Binds the target as the draw framebuffer (both attachments), (re)creating it for `size`.
  // Throws mvw::Error if the GL cannot render into it.
  void bind(glm::ivec2 size);

  // The pixels and depths of the bound target, top row first, then unbinds it.
  Image read() const;

 private:
  glm::ivec2 size_{0};
  Texture colour_, depth_;
  Framebuffer framebuffer_;
};

}  // namespace mvw::render::detail
