#pragma once
// What the window loop writes of its frames: the frame log (mvw view --frame-log) and a pane's
// rectangle of the window's image (the script's pane screenshots).
#include <chrono>
#include <filesystem>
#include <fstream>

#include <glm/vec2.hpp>

#include "mvw/core/Image.h"

namespace mvw::viewer {

// One CSV line per drawn frame: frame, ms since the previous frame's swap, the 3D pane's render
// ms and size where it rendered, interactive, drag divisor.
class FrameLog {
 public:
  // An empty path: no log. Opened (and its header written) before the window: a path that
  // cannot be written is bad input (InputError) with nothing drawn.
  explicit FrameLog(const std::filesystem::path& file);
  // The frames' clock starts (the window is open).
  void start() { last_ = std::chrono::steady_clock::now(); }
  // A frame swapped: its line, flushed (a watcher sees the viewer live). Nothing without a log.
  void frame(int frame, double render3dMs, glm::ivec2 render3dSize, bool interactive, int divisor);

 private:
  std::ofstream out_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// The pane's rectangle (origin and size in window pixels, y down) of the window's image,
// clipped to the window.
Image paneImage(const Image& window, glm::ivec2 origin, glm::ivec2 size);

}  // namespace mvw::viewer
