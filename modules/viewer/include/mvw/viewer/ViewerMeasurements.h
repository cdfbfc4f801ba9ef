#pragma once
// The measurements on the MPR panes: the mouse tool, the sphere or ruler a drag draws, the
// spheres and rulers taken (saved with the state as the study's "measurements", restored on
// opening), each sphere's statistics in both volumes, and where each shape shows on a pane.
// It sees the panes only through PaneGeometry, and is told the functional volume's placement;
// it knows nothing else of the viewer's state.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/study/RoiStatistics.h"
#include "mvw/viewer/PaneGeometry.h"

namespace mvw::viewer {

// What the mouse does on an MPR pane: move the crosshair (the default), draw a sphere ROI
// (press: the centre on the plane; the drag's length: the radius in mm) or a ruler (press: one
// end, release: the other). Shift-drag draws a sphere and Alt-drag a ruler whatever the tool.
enum class MprTool { Crosshair, Sphere, Ruler };

// A sphere ROI's statistics in each volume, by study::roiStatistics (as `mvw stats --sphere`):
// the anatomical one in its unit, the functional one (in SUV with SUVpeak for PET) at the
// sphere's centre moved by the placement into the functional volume's world. An ROI that
// holds no voxel centre of a volume says so instead.
struct SphereStatistics {
  std::optional<study::RoiStats> anatomical, functional;
  std::string anatomicalProblem, functionalProblem;
  glm::dvec3 functionalCentre{0.0};
};

// A sphere or a ruler as one pane shows it: in fractions of the pane (y down).
struct PaneCircle {
  glm::dvec2 centre{0.0};
  glm::dvec2 radius{0.0};  // x and y radii in fractions of the pane's width and height
  double radiusMm = 0.0;   // of the circle the plane cuts
};
struct PaneSegment {
  glm::dvec2 from{0.0}, to{0.0};
  bool inPlane = false;  // both ends lie on the pane's plane (within half a slice)
};

class ViewerMeasurements {
 public:
  // `panes` (the viewer's state) and the volumes must outlive this. anatomicalFromFunctional:
  // the functional volume's placement (world LPS mm to world), for the functional statistics.
  ViewerMeasurements(const PaneGeometry& panes, const Volume& anatomical, const Volume* functional,
                     const glm::dmat4& anatomicalFromFunctional);
  ViewerMeasurements(const ViewerMeasurements&) = delete;
  ViewerMeasurements& operator=(const ViewerMeasurements&) = delete;

  void setTool(MprTool tool) { tool_ = tool; }
  MprTool tool() const { return tool_; }
  // A mouse gesture on an MPR pane with a tool other than the crosshair, in fractions of the
  // pane: press, moves (the pending sphere or ruler follows, on the pane's plane), release (it
  // is added; a sphere of radius 0 is not). On the 3D pane or with the crosshair: nothing.
  void beginGesture(int pane, MprTool tool, double x, double y);
  void moveGesture(double x, double y);
  void endGesture();
  bool measuring() const { return pending_.has_value(); }
  // The pending gesture's sphere (radius so far) or ruler, for the panes to draw.
  std::optional<config::SphereMeasurement> pendingSphere() const;
  std::optional<config::RulerMeasurement> pendingRuler() const;

  void addSphere(const config::SphereMeasurement& sphere);  // statistics computed at once
  void addRuler(const config::RulerMeasurement& ruler);
  void clear();  // every sphere and ruler, and a pending gesture
  // The spheres and rulers taken, as the study config saves them.
  const config::Measurements& all() const { return measurements_; }
  const std::vector<SphereStatistics>& sphereStatistics() const { return sphereStats_; }
  // The functional volume placed anew (a registration re-run): each functional ROI moves with
  // it, and its statistics are computed again.
  void setPlacement(const glm::dmat4& anatomicalFromFunctional);
  static double rulerLengthMm(const config::RulerMeasurement& ruler);

  // Where a sphere cuts the pane's plane (nothing where it misses it, on the 3D pane and before
  // the pane's first frame), where a ruler lies.
  std::optional<PaneCircle> paneCircle(int pane, const config::SphereMeasurement& sphere) const;
  PaneSegment paneSegment(int pane, const config::RulerMeasurement& ruler) const;
  // Where a world point shows on the pane's last frame: fractions of its width and height (y
  // down), 0.5 at its middle (the cursor readout and the crosshair are drawn there).
  glm::dvec2 toPane(int pane, const glm::dvec3& world) const;
  // Every sphere's statistics as `mvw stats --json` names the fields (tests compare the two).
  void writeSphereStatistics(const std::filesystem::path& file) const;

 private:
  struct Gesture {
    int pane = kAxial;
    MprTool tool = MprTool::Sphere;
    glm::dvec3 from{0.0}, to{0.0};
  };
  SphereStatistics computeStatistics(const config::SphereMeasurement& sphere) const;

  const PaneGeometry& panes_;
  const Volume& anatomical_;
  const Volume* functional_;
  glm::dmat4 anatomicalFromFunctional_;
  MprTool tool_ = MprTool::Crosshair;
  std::optional<Gesture> pending_;
  config::Measurements measurements_;
  std::vector<SphereStatistics> sphereStats_;  // one per measurements_.spheres
};

}  // namespace mvw::viewer
