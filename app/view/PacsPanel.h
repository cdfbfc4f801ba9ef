#pragma once
// The viewer's PACS window (Dear ImGui, issue 37 item 3): the server, the search, the studies
// found, the chosen study's series with the role each takes (anatomical, functional,
// segmentation), the registration rule, Open, and what the background step does or why it
// failed. Everything it changes goes through viewer::PacsBrowser.
#include "mvw/viewer/PacsBrowser.h"

namespace mvw::app {

class PacsPanel {
 public:
  PacsPanel(viewer::PacsBrowser& browser, float scale) : browser_(browser), scale_(scale) {}

  bool visible() const { return visible_; }
  void setVisible(bool on) { visible_ = on; }
  // Between ImGui::NewFrame and ImGui::Render, after the viewer's own window (this one lies
  // over the panes). left: where the panes start (the control panel's right edge).
  void draw(float left);

 private:
  void drawSearch();
  void drawStudies();
  void drawSeries();
  void drawOpen();

  viewer::PacsBrowser& browser_;
  float scale_ = 1.0f;
  bool visible_ = false;
};

}  // namespace mvw::app
