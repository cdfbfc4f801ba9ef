#include "mvw/viewer/ViewerFrames.h"

#include <algorithm>

#include <glm/common.hpp>

#include "mvw/core/Error.h"

namespace mvw::viewer {

FrameLog::FrameLog(const std::filesystem::path& file) {
  if (file.empty()) return;
  out_.open(file, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(file, "cannot write the frame log");
  out_ << "frame,ms,render3d_ms,render3d_width,render3d_height,interactive,drag_divisor\n";
}

void FrameLog::frame(int frame, double render3dMs, glm::ivec2 render3dSize, bool interactive,
                     int divisor) {
  if (!out_.is_open()) return;
  const auto now = std::chrono::steady_clock::now();
  out_ << frame << ',' << std::chrono::duration<double, std::milli>(now - last_).count() << ','
       << render3dMs << ',' << render3dSize.x << ',' << render3dSize.y << ','
       << (interactive ? 1 : 0) << ',' << divisor << '\n'
       << std::flush;
  last_ = now;
}

Image paneImage(const Image& window, glm::ivec2 origin, glm::ivec2 size) {
  const glm::ivec2 lo = glm::clamp(origin, glm::ivec2(0), glm::ivec2(window.width, window.height));
  const glm::ivec2 hi =
      glm::clamp(origin + size, glm::ivec2(0), glm::ivec2(window.width, window.height));
  Image pane(hi.x - lo.x, hi.y - lo.y);
  for (int y = 0; y < pane.height; ++y)
    std::copy_n(window.pixel(lo.x, lo.y + y), 4 * pane.width, pane.pixel(0, y));
  return pane;
}

}  // namespace mvw::viewer
