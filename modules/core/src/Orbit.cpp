#include "mvw/core/Orbit.h"

#include <cmath>

namespace mvw {

std::vector<double> orbitAzimuths(const Orbit& orbit, double azimuthDeg) {
  std::vector<double> azimuths;
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < orbit.frames; ++k) {
    const double phase = static_cast<double>(k) / orbit.frames;
    azimuths.push_back(orbit.mode == OrbitMode::Spin
                           ? azimuthDeg + 360.0 * phase
                           : azimuthDeg + orbit.rangeDeg * std::sin(2.0 * kPi * phase));
  }
  return azimuths;
}

}  // namespace mvw
