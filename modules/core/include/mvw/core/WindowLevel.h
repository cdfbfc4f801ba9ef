#pragma once
// The grey-level window of a projection or MPR: width and centre in the volume's unit. A
// window that is not positive means "the full value range", the one fallback every view uses.
namespace mvw {

struct WindowLevel {
  double window = 0.0;
  double level = 0.0;
};

// `window` > 0: (window, level) as given; otherwise the range [lo, hi].
WindowLevel windowOrFullRange(double window, double level, double lo, double hi);

}  // namespace mvw
