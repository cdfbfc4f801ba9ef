#pragma once
// The transfer function as the ray caster reads it (internal to mvw_render): a 2D table over
// the value range (x) and, for a 2D function, the gradient magnitude (y), its opacities
// corrected for the frame's step once here rather than per sample.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "GlObjects.h"
#include "mvw/render/TransferFunction.h"

namespace mvw::render::detail {

class TransferTable {
 public:
  static constexpr int kEntries = 1024;

  TransferTable();  // the context must be current

  // Where a value sits in the table, and back: entry i holds the value lo + i (hi - lo) /
  // (kEntries - 1). The shader's lookup (uTransferRange puts entry i at its texel centre),
  // block visibility (BlockGrid) and the visible value range below all follow it.
  static double entryOf(double value, double lo, double hi) {
    return (value - lo) / (hi - lo) * (kEntries - 1);
  }
  static double valueOf(double entry, double lo, double hi) {
    return lo + entry * ((hi - lo) / (kEntries - 1));
  }

  // Samples `transfer` over lo..hi and uploads the table for a ray step of stepMm (opacities
  // are per referenceStepMm). gradientHigh > 0: opacity also scaled by
  // smoothstep(gradientLow, gradientHigh, |gradient|), over 64 rows up to 2 gradientHigh.
  void update(const TransferFunction& transfer, double lo, double hi, double stepMm,
              double referenceStepMm, double gradientLow, double gradientHigh);

  // The sampled function before step correction (what block visibility asks about).
  const std::vector<glm::vec4>& lut() const { return lut_; }
  // 1 / the gradient magnitude of the table's last row: maps |gradient| to the table's y.
  double gradientScale() const { return gradientScale_; }
  int rows() const { return rows_; }
  // The values (lo..hi units) from the first to the last entry with some opacity, widened by
  // an entry either side (what linear filtering reads), unbounded on a side whose end entry
  // has some; min > max where none has any.
  glm::vec2 visibleValues() const { return visibleValues_; }
  GLuint texture() const { return texture_.id(); }

 private:
  Texture texture_;
  std::vector<glm::vec4> lut_;
  double gradientScale_ = 1.0;
  int rows_ = 1;
  glm::vec2 visibleValues_{1.0f, 0.0f};
};

}  // namespace mvw::render::detail
