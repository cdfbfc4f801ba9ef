#include "mvw/core/Orientation.h"

#include <cmath>
#include <numbers>

namespace mvw {

namespace {
int dominantAxis(const glm::dvec3& v) {
  int best = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(v[a]) > std::abs(v[best])) best = a;
  return best;
}
}  // namespace

std::string orientationCode(const glm::dmat3& direction) {
  static constexpr char kToward[3][2] = {{'L', 'R'}, {'P', 'A'}, {'S', 'I'}};
  std::string code;
  for (int c = 0; c < 3; ++c) {
    const glm::dvec3 axis = direction[c];
    const int a = dominantAxis(axis);
    code += axis[a] >= 0 ? kToward[a][0] : kToward[a][1];
  }
  return code;
}

bool isOblique(const glm::dmat3& direction, double toleranceDegrees) {
  const double cosTol = std::cos(toleranceDegrees * std::numbers::pi / 180.0);
  for (int c = 0; c < 3; ++c) {
    const glm::dvec3 axis = glm::normalize(direction[c]);
    if (std::abs(axis[dominantAxis(axis)]) < cosTol) return true;
  }
  return false;
}

}  // namespace mvw
