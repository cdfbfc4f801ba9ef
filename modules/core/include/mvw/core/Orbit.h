#pragma once
// A rotating view (a PET reader's rotating MIP): the camera turns about the patient's long axis
// (S), a full turn (spin) or back and forth (rock), one value for the study config's view
// (config::ViewConfig: "orbit", "orbit_mode", "orbit_range", "orbit_fps") and the viewer's
// rotating 3D pane (viewer::ViewerOrbit), which turn through the same angles. Its keys, ranges
// and defaults: the config's orbit table (modules/config, docs/config-reference.md).
#include <vector>

namespace mvw {

enum class OrbitMode { Spin, Rock };
inline constexpr int kMaxOrbitFrames = 720;

struct Orbit {
  // 0: a still; N in 2..kMaxOrbitFrames frames from the view's azimuth on.
  int frames = 0;
  OrbitMode mode = OrbitMode::Spin;
  double rangeDeg = 30.0;  // rock: how far it swings each way
  double fps = 10.0;       // the movie's frames per second
  bool on() const { return frames > 0; }
  bool operator==(const Orbit&) const = default;
};

// The azimuths (degrees) of its frames from `azimuthDeg`: spin azimuthDeg + 360 k / N, rock
// azimuthDeg + rangeDeg sin(2 pi k / N); empty for a still.
std::vector<double> orbitAzimuths(const Orbit& orbit, double azimuthDeg);

}  // namespace mvw
