#pragma once
// The viewer's four panes, and where an MPR pane shows the world, as the parts of the viewer's
// state that draw on the panes see them (ViewerMeasurements). ViewerState answers from its last
// frames' cameras and the crosshair; a part that takes this interface instead of the state
// depends on nothing else of it, and reads in isolation.
#include <glm/vec3.hpp>

#include "mvw/render/Camera.h"

namespace mvw::viewer {

enum Pane { k3d = 0, kAxial, kCoronal, kSagittal, kPaneCount };

class PaneGeometry {
 public:
  virtual ~PaneGeometry() = default;

  // The camera of the pane's last frame (a default camera before its first): an MPR pane's
  // forward is its plane's normal, and clipFromWorld places a world point on the pane.
  virtual const render::Camera& paneCamera(int pane) const = 0;
  virtual bool paneRendered(int pane) const = 0;  // has had a frame
  // The linked crosshair: every MPR pane's plane passes through it.
  virtual const glm::dvec3& crosshair() const = 0;
  // The world point under (x, y) of an MPR pane (fractions of the pane, y down), on its plane.
  virtual glm::dvec3 onPlane(int pane, double x, double y) const = 0;
};

}  // namespace mvw::viewer
