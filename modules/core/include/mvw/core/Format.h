#pragma once
// Numbers as messages and notes show them.
#include <cstdio>
#include <string>

namespace mvw {

// %g with `significant` digits: 1e-300 and 1e+300, 0.5 and 2, not 0.000000, 300 digits or
// 0.500000 (std::to_string's %f).
inline std::string shortNumber(double x, int significant = 6) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", significant, x);
  return text;
}

}  // namespace mvw
