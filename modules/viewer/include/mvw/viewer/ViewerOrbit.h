#pragma once
// The rotating 3D view: off, a full turn (spin) or back and forth (rock) about the patient's
// long axis, one step per drawn frame, through the same angles `mvw render --orbit` renders.
// It keeps only the angles: ViewerState turns the 3D camera to them, and a drag or a reset
// that takes the camera stops it.
#include <cstddef>
#include <optional>
#include <vector>

#include "mvw/core/Orbit.h"

namespace mvw::viewer {

enum class Orbit { Off, Spin, Rock };

class ViewerOrbit {
 public:
  // Spin turns 360 degrees in kFrames frames; rock swings +-kRockRangeDeg about the azimuth
  // it started from.
  static constexpr int kFrames = 90;
  static constexpr double kRockRangeDeg = 30.0;

  // Starts `orbit` from `azimuthDeg` (the angle shown now), from its first step; Off stops it
  // (the camera stays at the angle shown, so a reader can stop where a finding shows best).
  void start(Orbit orbit, double azimuthDeg);
  Orbit mode() const;
  // The rotation it runs (mvw/core/Orbit.h, what a view's "orbit" keys say): off while off.
  const mvw::Orbit& turn() const { return turn_; }
  // The next frame's azimuth in degrees; nothing while off.
  std::optional<double> advance();

 private:
  mvw::Orbit turn_;
  std::vector<double> azimuths_;  // one turn or swing, from the starting azimuth
  std::size_t step_ = 0;
};

}  // namespace mvw::viewer
