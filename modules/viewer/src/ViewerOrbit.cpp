#include "mvw/viewer/ViewerOrbit.h"

#include "mvw/config/StudyConfig.h"

namespace mvw::viewer {

void ViewerOrbit::start(Orbit orbit, double azimuthDeg) {
  mode_ = orbit;
  azimuths_.clear();
  step_ = 0;
  if (orbit == Orbit::Off) return;
  // The same angles `mvw render --orbit` renders, from the azimuth shown now.
  config::ViewConfig v;
  v.azimuth = azimuthDeg;
  v.orbit = kFrames;
  v.orbitMode = orbit == Orbit::Spin ? config::OrbitMode::Spin : config::OrbitMode::Rock;
  v.orbitRangeDeg = kRockRangeDeg;
  azimuths_ = config::orbitAzimuths(v);
}

std::optional<double> ViewerOrbit::advance() {
  if (mode_ == Orbit::Off || azimuths_.empty()) return std::nullopt;
  step_ = (step_ + 1) % azimuths_.size();
  return azimuths_[step_];
}

}  // namespace mvw::viewer
