#pragma once
// The viewer's Dear ImGui user interface: the control panel on the left, the four panes (or
// the maximised one) with the linked crosshair, and the mouse and keys over them. Everything
// it changes goes through viewer::ViewerState; it draws the panes' textures as the window loop
// uploaded them.
#include <array>
#include <functional>
#include <utility>

#include <glm/vec3.hpp>

#include "mvw/render/DisplayTexture.h"
#include "mvw/viewer/ViewerState.h"

struct ImVec2;

namespace mvw::app {

class ViewerPanel {
 public:
  using PaneTextures = std::array<render::DisplayTexture, viewer::kPaneCount>;
  // scale: the UI scale (mvw view --ui-scale); the panel's width grows with it.
  ViewerPanel(viewer::ViewerState& state, const PaneTextures& textures, float scale = 1.0f)
      : state_(state), textures_(textures), scale_(scale) {}

  // Between ImGui::NewFrame and ImGui::Render; returns whether a pane is being dragged
  // (the 3D pane then renders coarse).
  bool draw();
  // What the panel's "Open from the PACS" button does (no button without it).
  void setOpenPacs(std::function<void()> open) { openPacs_ = std::move(open); }

 private:
  void drawPane(int pane, ImVec2 pos, ImVec2 size);
  // The control panel, one function per section.
  void drawControls();
  void drawViewControls();
  void drawDepthCue();
  void drawFunctionalControls();  // with a functional volume only
  void drawFunctionalWindow();
  void drawGlyphControls();
  void drawRegistration();
  void drawCrosshair();
  void drawMeasurementControls();
  void drawHelp();
  void drawMeasurements(int pane, ImVec2 pos, ImVec2 size);  // spheres and rulers on an MPR pane

  viewer::ViewerState& state_;
  const PaneTextures& textures_;
  float scale_ = 1.0f;
  bool dragging_ = false;
  std::function<void()> openPacs_;
};

}  // namespace mvw::app
