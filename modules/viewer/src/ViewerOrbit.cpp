#include "mvw/viewer/ViewerOrbit.h"

namespace mvw::viewer {

void ViewerOrbit::start(Orbit orbit, double azimuthDeg) {
  turn_ = mvw::Orbit{};
  step_ = 0;
  if (orbit != Orbit::Off)
    turn_ = {kFrames, orbit == Orbit::Spin ? OrbitMode::Spin : OrbitMode::Rock, kRockRangeDeg};
  // The same angles `mvw render --orbit` renders, from the azimuth shown now.
  azimuths_ = orbitAzimuths(turn_, azimuthDeg);
}

Orbit ViewerOrbit::mode() const {
  if (!turn_.on()) return Orbit::Off;
  return turn_.mode == OrbitMode::Spin ? Orbit::Spin : Orbit::Rock;
}

std::optional<double> ViewerOrbit::advance() {
  if (azimuths_.empty()) return std::nullopt;
  step_ = (step_ + 1) % azimuths_.size();
  return azimuths_[step_];
}

}  // namespace mvw::viewer
