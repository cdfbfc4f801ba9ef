#pragma once
// `mvw view`: a 3D view and the three orthogonal MPR views with a linked crosshair, and a
// control panel (Dear ImGui), on the same renderer and shaders as the headless path.
#include <filesystem>

#include "mvw/pacs/Pacs.h"
#include "mvw/viewer/ViewerLaunch.h"

namespace mvw::app {

struct ViewerOptions {
  // The study, loaded, and the PACS servers (viewer::launchViewer); without a study the window
  // opens on the PACS window alone.
  viewer::ViewerLaunch launch;
  // The command line's --cache and time-outs: the PACS window's searches and retrieves use them.
  pacs::Options pacs;
  std::filesystem::path script;  // scripted events, for tests (see mvw/viewer/ViewerScript.h)
  // One CSV line per drawn frame (frame, ms since the previous frame's swap, the 3D pane's
  // render ms and size where it rendered, interactive, drag divisor); empty: none.
  std::filesystem::path frameLog;
  int width = 1400, height = 900;
  // The panel's text and controls (ImGui's font and sizes) and the panel's width scaled by this.
  double uiScale = 1.0;
};

// Runs until the window closes or the script says quit; returns the process exit code.
int runViewer(ViewerOptions options);

}  // namespace mvw::app
