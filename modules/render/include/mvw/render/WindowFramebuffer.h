#pragma once
// The default framebuffer of a context (the window's, for the viewer): cleared before a frame
// is drawn and read back for screenshots. It owns no GL object (name 0 belongs to the
// context), so it is a non-copyable handle on the context, which must outlive it.
#include <glm/vec4.hpp>

#include "mvw/core/Image.h"
#include "mvw/render/GlContext.h"

namespace mvw::render {

class WindowFramebuffer {
 public:
  explicit WindowFramebuffer(GlContext& context) : context_(&context) {}
  WindowFramebuffer(const WindowFramebuffer&) = delete;
  WindowFramebuffer& operator=(const WindowFramebuffer&) = delete;
  WindowFramebuffer(WindowFramebuffer&&) noexcept = default;
  WindowFramebuffer& operator=(WindowFramebuffer&&) noexcept = default;

  // Binds it, sets the viewport to the context's whole size and clears the colour buffer.
  void clear(const glm::vec4& colour);
  // The buffer being drawn (a window's back buffer before the swap), row 0 = top.
  Image read() const;

 private:
  GlContext* context_;
};

}  // namespace mvw::render
