#pragma once
// The functional volume on the GPU (internal to mvw_render) on its own grid, with the
// registration that places it and the colour map that fuses it over the anatomy; shaders
// sample it through common/functional.glsl.
#include <cstdint>
#include <optional>
#include <utility>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "GlObjects.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render::detail {

class FunctionalTextures {
 public:
  // Uploads `functional` (component 0; labels nearest, other attributes trilinear) placed by
  // anatomicalFromFunctional (functional world -> anatomical world, LPS mm). Context current.
  void set(const Volume& functional, const glm::dmat4& anatomicalFromFunctional);

  bool present() const { return functional_.id() != 0; }
  // The value range (one unit wide when flat), and a counter of set() calls, so that what is
  // derived from the volume knows when to derive it again.
  std::pair<double, double> range() const { return range_; }
  std::uint64_t generation() const { return generation_; }

  // The values mapped to 0..1: low..high when low < high, otherwise the value range.
  glm::vec2 window(const ValueWindow& w) const;
  // uFunctionalFromWorld, uFunctionalRange (= window) and uFunctionalClasses of `program`.
  void setUniforms(const ShaderProgram& program, glm::vec2 window, int classes) const;

  GLuint texture() const { return functional_.id(); }
  // The overlay's colour map: hot metal (interpolated, as always) or `table` (nearest: a
  // palette's entries are shown as they are). Uploaded only when it changes.
  GLuint colormap(const std::optional<ColorTable>& table);

 private:
  Texture functional_, colormap_, customColormap_;
  std::optional<ColorTable> custom_;
  std::uint64_t generation_ = 0;
  glm::dmat4 textureFromAnatomicalWorld_{1.0};
  std::pair<double, double> range_{0.0, 1.0};
};

}  // namespace mvw::render::detail
