#pragma once
// The legend of outlined segments, burned into annotated MPR renders: one line per segment,
// its name in its colour, at the top left under the orientation label.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mvw/core/Image.h"

namespace mvw::render {

struct LegendEntry {
  std::string name;
  glm::vec3 colour{1.0f};  // sRGB 0..1
};

void drawSegmentLegend(Image& image, const std::vector<LegendEntry>& entries);

}  // namespace mvw::render
