#include "mvw/core/WindowLevel.h"

namespace mvw {

WindowLevel windowOrFullRange(const WindowLevel& window, double lo, double hi) {
  if (window.set()) return window;
  return {hi - lo, 0.5 * (hi + lo)};
}

}  // namespace mvw
