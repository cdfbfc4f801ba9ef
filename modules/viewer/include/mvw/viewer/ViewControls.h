#pragma once
// What the panel's sliders do to the 3D view's settings where a value is more than the one
// field it shows (app/view draws the sliders; ViewerState marks the panes dirty).
#include <utility>

#include "mvw/render/RenderSettings.h"

namespace mvw::viewer {

// The blue-noise glyphs' spacing in mm, as the diameter and the map's spacing give it.
double glyphSpacingMm(const render::RenderSettings& v);
// Another spacing: the diameter follows at its default fraction, and the map is made again
// (its seed kept).
void setGlyphSpacingMm(render::RenderSettings& v, double spacingMm);

// The functional attribute's window shown: the user's where set (high above low), else `range`.
ValueWindow functionalWindow(const render::RenderSettings& v, std::pair<double, double> range);
// The user's window, kept a millionth of `range` wide at least.
void setFunctionalWindow(render::RenderSettings& v, double low, double high,
                         std::pair<double, double> range);

}  // namespace mvw::viewer
