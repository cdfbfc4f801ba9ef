#include "mvw/render/Framing.h"

#include <glm/geometric.hpp>

namespace mvw::render {

FramingSphere framingSphere(const Volume& volume) {
  const glm::dmat4& worldFromIndex = volume.worldFromIndex();
  const glm::dvec3 dims(volume.dimensions());
  const glm::dvec3 corner0(worldFromIndex * glm::dvec4(-0.5, -0.5, -0.5, 1.0));
  const glm::dvec3 corner1(worldFromIndex * glm::dvec4(dims - 0.5, 1.0));
  // The diagonal from the spacing rather than the corners: the same length for an orthonormal
  // direction matrix, and the value every golden image was rendered with.
  return {0.5 * (corner0 + corner1), 0.5 * glm::length(dims * volume.spacing())};
}

double defaultStepMm(const Volume& volume) { return 0.5 * volume.smallestSpacing(); }

}  // namespace mvw::render
