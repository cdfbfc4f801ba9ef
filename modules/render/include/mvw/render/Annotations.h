#pragma once
// Text and marks burned into headless renders (OpenCV Hershey fonts): orientation labels at
// the four edges, a scale bar in mm (orthographic views), and a caption (mode, window/level).
#include <string>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Image.h"
#include "mvw/render/Camera.h"

namespace mvw::render {

// The patient side a world (LPS) direction points toward: "L", "P", "S", ... with a second
// letter for directions more than ~22 degrees off the main axis ("LA").
std::string orientationLabel(const glm::dvec3& worldDirection);

void annotate(Image& image, const Camera& camera, const std::string& caption);

// A vertical colour bar (hot metal, or `table`) at the right edge, labelled with the value range.
void drawColourBar(Image& image, double lo, double hi, const std::string& unit);
void drawColourBar(Image& image, double lo, double hi, const std::string& unit,
                   const ColorTable& table);

}  // namespace mvw::render
