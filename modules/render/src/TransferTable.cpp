#include "TransferTable.h"

#include <algorithm>
#include <cmath>

namespace mvw::render::detail {

TransferTable::TransferTable() : texture_(makeTexture()) {}

void TransferTable::update(const TransferFunction& transfer, double lo, double hi, double stepMm,
                           double referenceStepMm, double gradientLow, double gradientHigh) {
  lut_ = sampleTransferFunction(transfer, lo, hi, kEntries, lo, hi);
  const bool transfer2d = gradientHigh > 0.0;
  const int rows = transfer2d ? 64 : 1;
  rows_ = rows;
  int first = kEntries, last = -1;
  for (int i = 0; i < kEntries; ++i)
    if (lut_[i].a > 0.0f) {
      first = std::min(first, i);
      last = i;
    }
  // Values beyond lo..hi read the end entries (the lookup clamps).
  visibleValues_ =
      last < 0 ? glm::vec2(1.0f, 0.0f)
               : glm::vec2(first == 0 ? -3.4e38f : float(valueOf(first - 1, lo, hi)),
                           last == kEntries - 1 ? 3.4e38f : float(valueOf(last + 1, lo, hi)));
  const double gradientMax = transfer2d ? 2.0 * gradientHigh : 1.0;
  gradientScale_ = 1.0 / gradientMax;
  std::vector<glm::vec4> table(static_cast<std::size_t>(kEntries) * rows);
  for (int r = 0; r < rows; ++r) {
    double scale = 1.0;
    if (transfer2d) {
      const double g = gradientMax * r / (rows - 1);
      const double x =
          std::clamp((g - gradientLow) / std::max(1e-9, gradientHigh - gradientLow), 0.0, 1.0);
      scale = x * x * (3.0 - 2.0 * x);
    }
    for (int i = 0; i < kEntries; ++i) {
      glm::vec4 c = lut_[i];
      const double a = std::min(0.999999, c.a * scale);
      c.a = static_cast<float>(1.0 - std::pow(1.0 - a, stepMm / referenceStepMm));
      table[static_cast<std::size_t>(r) * kEntries + i] = c;
    }
  }
  glBindTexture(GL_TEXTURE_2D, texture_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kEntries, rows, 0, GL_RGBA, GL_FLOAT, table.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace mvw::render::detail
