#include "BoxProxy.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace mvw::render::detail {

BoxProxy boxProxy(const Camera& camera, const glm::dmat4& textureFromWorld, glm::dvec3 boxMin,
                  glm::dvec3 boxMax) {
  constexpr double kMargin = 0.01;
  BoxProxy p;
  p.min = boxMin - kMargin;
  p.max = boxMax + kMargin;
  const glm::dmat4 worldFromTexture = glm::inverse(textureFromWorld);
  p.clipFromTexture = camera.clipFromWorld * worldFromTexture;
  if (camera.perspective)
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 c((corner & 1) ? p.max.x : p.min.x, (corner & 2) ? p.max.y : p.min.y,
                         (corner & 4) ? p.max.z : p.min.z);
      if ((p.clipFromTexture * glm::dvec4(c, 1.0)).w <= 1e-6) return p;  // fullscreen
    }
  // A face's outward normal in world space is the texture axis through the transposed
  // textureFromWorld; it faces away from the viewer when the line of sight to it runs along
  // the normal.
  const glm::dmat3 normalFromTexture = glm::transpose(glm::dmat3(textureFromWorld));
  const glm::dvec3 centre = 0.5 * (p.min + p.max);
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const bool high = face & 1;
    glm::dvec3 axisDir(0.0), onFace = centre;
    axisDir[axis] = high ? 1.0 : -1.0;
    onFace[axis] = high ? p.max[axis] : p.min[axis];
    const glm::dvec3 normal = glm::normalize(normalFromTexture * axisDir);
    const glm::dvec3 sight =
        camera.perspective
            ? glm::normalize(glm::dvec3(worldFromTexture * glm::dvec4(onFace, 1.0)) - camera.eye)
            : camera.forward;
    if (glm::dot(normal, sight) > -1e-3) p.faces |= 1 << face;
  }
  p.fullscreen = false;
  return p;
}

}  // namespace mvw::render::detail
