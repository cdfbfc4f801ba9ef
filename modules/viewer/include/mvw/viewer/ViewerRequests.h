#pragma once
// What the viewer's state and its --script ask of the window loop, which acts on them once a
// frame is fully drawn: a screenshot of the window or of one pane, and to quit; and what the
// loop hears back: the status line the panel shows, and whether a scripted drag makes this
// frame interactive (the 3D pane then renders coarse, as under the mouse). It knows nothing of
// the panes or the volumes: the requests are only kept until the loop takes them.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

namespace mvw::viewer {

class ViewerRequests {
 public:
  // A screenshot is taken by the window once the frame is fully drawn.
  void requestScreenshot(std::filesystem::path file);
  std::optional<std::filesystem::path> takeScreenshotRequest();
  // The pane as the window shows it (its rectangle of the framebuffer: the render with its
  // annotations, and the crosshair on an MPR pane), taken as the whole-window screenshot is.
  void requestPaneScreenshot(int pane, std::filesystem::path file);
  std::optional<std::pair<int, std::filesystem::path>> takePaneScreenshotRequest();
  // A scripted drag in progress (ViewerScript's drag-frames): its frames are interactive, as
  // the frames of a mouse drag are.
  void setScriptedInteraction(bool on) { scriptedInteraction_ = on; }
  bool scriptedInteraction() const { return scriptedInteraction_; }
  void requestQuit() { quit_ = true; }
  bool quitRequested() const { return quit_; }
  void setStatus(std::string status) { status_ = std::move(status); }
  const std::string& status() const { return status_; }

 private:
  std::optional<std::filesystem::path> screenshot_;
  std::optional<std::pair<int, std::filesystem::path>> paneScreenshot_;
  bool scriptedInteraction_ = false;
  bool quit_ = false;
  std::string status_;
};

}  // namespace mvw::viewer
