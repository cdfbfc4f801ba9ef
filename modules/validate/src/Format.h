#pragma once
// Number formatting shared by the validator's messages and its report.
#include <cmath>
#include <cstdio>
#include <string>

namespace mvw::validate::detail {

// `digits` decimals; "inf" for infinities (an identical image's PSNR).
inline std::string fmt(double v, int digits) {
  if (!std::isfinite(v)) return "inf";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

}  // namespace mvw::validate::detail
