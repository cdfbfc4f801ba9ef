#pragma once
// The discrete maximum projection of Heidrich, McCool and Stevens (1995): n isosurface
// shells at emission thresholds, drawn with the GL depth test performing the maximum
// (internal to mvw_render; VolumeRenderer dispatches the shell modes here).
#include <map>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>

#include "GlObjects.h"
#include "IsoShells.h"
#include "mvw/core/DepthCue.h"
#include "mvw/core/Image.h"
#include "mvw/render/Camera.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render::detail {

enum class ShellMode { Maximum, Summation, Lit };

struct ShellDraw {
  ShellMode mode = ShellMode::Maximum;
  glm::ivec2 size{512, 512};
  Camera camera;
  glm::dvec3 centre{0.0};
  double radius = 1.0;
  double windowLow = 0.0, windowWidth = 1.0;  // values mapped to emission 0..1
  int count = 8;                              // shells at emission i / count, i = 1..count
  std::vector<bool> enabled;                  // per shell (empty: all)
  DepthCue depthCue;  // its values, whether or not it is on (off: the defaults, no cueing)
  glm::vec4 light{0.25f, 0.7f, 0.25f, 24.0f};
};

class ShellRenderer {
 public:
  ShellRenderer(std::vector<float> values, glm::ivec3 dims, const glm::dmat4& worldFromIndex);
  ~ShellRenderer();
  Image draw(const ShellDraw& d);
  std::size_t triangleCount() const;

 private:
  struct Gpu;
  void ensureShells(const ShellDraw& d);
  std::vector<float> values_;
  glm::ivec3 dims_;
  glm::dmat4 worldFromIndex_;
  double cachedLow_ = 0.0, cachedWidth_ = 0.0;
  int cachedCount_ = 0;
  std::vector<std::unique_ptr<Gpu>> shells_;
  std::map<ShellMode, ShaderProgram> programs_;  // compiled once per mode
};

}  // namespace mvw::render::detail
