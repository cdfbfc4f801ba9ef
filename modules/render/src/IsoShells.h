#pragma once
// Isosurface shells for the discrete maximum-projection algorithm of Heidrich, McCool and
// Stevens (1995), section 1.4: nested surfaces at emission thresholds, extracted with VTK's
// flying edges (internal to mvw_render; VTK stays in the .cpp).
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mvw::render::detail {

struct ShellMesh {
  double threshold = 0.0;       // value of the isosurface
  std::vector<float> vertices;  // x y z nx ny nz per vertex, world mm (LPS), unit outward normal
  std::vector<unsigned> indices;
};

// values: the volume (x fastest), dims, worldFromIndex.
ShellMesh extractShell(const std::vector<float>& values, glm::ivec3 dims,
                       const glm::dmat4& worldFromIndex, double threshold);

}  // namespace mvw::render::detail
