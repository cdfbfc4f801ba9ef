#include "mvw/core/WindowLevel.h"

namespace mvw {

WindowLevel windowOrFullRange(double window, double level, double lo, double hi) {
  if (window > 0) return {window, level};
  return {hi - lo, 0.5 * (hi + lo)};
}

}  // namespace mvw
