#include "mvw/render/TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mvw/core/Error.h"

namespace mvw::render {

namespace {

using P = TfPoint;

const std::vector<TransferFunction>& presets() {
  static const std::vector<TransferFunction> all = {
      {"ct-bone",
       false,
       {P{-1024, {0, 0, 0, 0}}, P{180, {0.80f, 0.65f, 0.50f, 0.0f}},
        P{350, {0.92f, 0.86f, 0.74f, 0.25f}}, P{1000, {1.0f, 0.98f, 0.94f, 0.85f}},
        P{3071, {1, 1, 1, 1}}}},
      {"ct-skin",
       false,
       {P{-1024, {0, 0, 0, 0}}, P{-500, {0.85f, 0.60f, 0.50f, 0.0f}},
        P{-300, {0.93f, 0.72f, 0.62f, 0.35f}}, P{200, {1.0f, 0.85f, 0.78f, 0.5f}},
        P{3071, {1, 1, 1, 0.8f}}}},
      {"ct-muscle-bone",
       false,
       {P{-1024, {0, 0, 0, 0}}, P{-50, {0.70f, 0.30f, 0.25f, 0.0f}},
        P{60, {0.80f, 0.32f, 0.26f, 0.05f}}, P{200, {0.88f, 0.55f, 0.45f, 0.08f}},
        P{400, {0.95f, 0.90f, 0.80f, 0.45f}}, P{3071, {1, 1, 1, 0.9f}}}},
      {"mr-default",
       true,
       {P{0.0, {0, 0, 0, 0}}, P{0.15, {0.55f, 0.45f, 0.40f, 0.0f}},
        P{0.4, {0.85f, 0.75f, 0.68f, 0.12f}}, P{1.0, {1, 1, 1, 0.6f}}}},
      {"pet-hot-metal",
       true,
       {P{0.0, {0, 0, 0, 0}}, P{0.3, {0.5f, 0.0f, 0.0f, 0.0f}}, P{0.6, {1.0f, 0.4f, 0.0f, 0.15f}},
        P{0.85, {1.0f, 0.85f, 0.2f, 0.4f}}, P{1.0, {1, 1, 1, 0.7f}}}},
  };
  return all;
}

}  // namespace

TransferFunction transferPreset(const std::string& name) {
  for (const auto& tf : presets())
    if (tf.name == name) return tf;
  std::string list;
  for (const auto& n : transferPresetNames()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown transfer function preset '" + name + "' (known: " + list + ")");
}

std::vector<std::string> transferPresetNames() {
  std::vector<std::string> names;
  for (const auto& tf : presets()) names.push_back(tf.name);
  return names;
}

std::vector<glm::vec4> sampleTransferFunction(const TransferFunction& tf, double lo, double hi,
                                              int n, double rangeLo, double rangeHi) {
  std::vector<glm::vec4> lut(static_cast<std::size_t>(n), glm::vec4(0.0f));
  if (tf.points.empty()) return lut;
  auto at = [&](const TfPoint& p) {
    return tf.relative ? rangeLo + p.value * (rangeHi - rangeLo) : p.value;
  };
  for (int i = 0; i < n; ++i) {
    const double v = lo + (hi - lo) * (n > 1 ? static_cast<double>(i) / (n - 1) : 0.0);
    if (v <= at(tf.points.front())) {
      lut[i] = tf.points.front().rgba;
      continue;
    }
    if (v >= at(tf.points.back())) {
      lut[i] = tf.points.back().rgba;
      continue;
    }
    for (std::size_t k = 1; k < tf.points.size(); ++k) {
      const double a = at(tf.points[k - 1]), b = at(tf.points[k]);
      if (v <= b) {
        const float w = b > a ? static_cast<float>((v - a) / (b - a)) : 1.0f;
        lut[i] = tf.points[k - 1].rgba * (1.0f - w) + tf.points[k].rgba * w;
        break;
      }
    }
  }
  return lut;
}

ColorTable hotMetalTable() {
  const auto lut = sampleTransferFunction(transferPreset("pet-hot-metal"), 0.0, 1.0, 256, 0.0, 1.0);
  ColorTable t;
  t.map = ColorMap::HotMetal;
  for (std::size_t i = 0; i < 256; ++i)
    for (int c = 0; c < 3; ++c)
      t.rgb[i][static_cast<std::size_t>(c)] =
          static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(lut[i][c], 0.0f, 1.0f)));
  return t;
}

}  // namespace mvw::render
