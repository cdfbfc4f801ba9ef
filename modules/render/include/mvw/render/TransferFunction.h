#pragma once
// 1D transfer functions: piecewise-linear colour and opacity over the volume's values.
// Opacity is per reference step (the volume's smallest voxel spacing); the ray caster
// corrects it for the actual step (alpha' = 1 - (1 - alpha)^(step / reference)).
// A "relative" function places its points on 0..1 of the volume's value range (MR, PET,
// whose units vary); an absolute one in the volume's unit (HU for the CT presets).
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "mvw/core/ColorMap.h"

namespace mvw::render {

struct TfPoint {
  double value = 0.0;
  glm::vec4 rgba{0.0f};  // colour 0..1, opacity per reference step
};

struct TransferFunction {
  std::string name;
  bool relative = false;
  std::vector<TfPoint> points;  // sorted by value
};

// ct-bone, ct-skin, ct-muscle-bone, mr-default, pet-hot-metal. Throws mvw::Error for others.
TransferFunction transferPreset(const std::string& name);
std::vector<std::string> transferPresetNames();

// n RGBA entries evenly spaced over [lo, hi] (absolute values); constant outside the points.
// The pet-hot-metal preset's colours as a 256-entry table (ColorMap::HotMetal, the functional
// overlay's default).
ColorTable hotMetalTable();

std::vector<glm::vec4> sampleTransferFunction(const TransferFunction& tf, double lo, double hi,
                                              int n, double rangeLo, double rangeHi);

}  // namespace mvw::render
