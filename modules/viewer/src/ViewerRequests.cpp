#include "mvw/viewer/ViewerRequests.h"

namespace mvw::viewer {

void ViewerRequests::requestScreenshot(std::filesystem::path file) {
  screenshot_ = std::move(file);
}

// Taking a request clears it: the window writes each screenshot once.
std::optional<std::filesystem::path> ViewerRequests::takeScreenshotRequest() {
  return std::exchange(screenshot_, std::nullopt);
}

void ViewerRequests::requestPaneScreenshot(int pane, std::filesystem::path file) {
  paneScreenshot_ = {pane, std::move(file)};
}

std::optional<std::pair<int, std::filesystem::path>> ViewerRequests::takePaneScreenshotRequest() {
  return std::exchange(paneScreenshot_, std::nullopt);
}

}  // namespace mvw::viewer
