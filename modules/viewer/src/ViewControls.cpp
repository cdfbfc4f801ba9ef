#include "mvw/viewer/ViewControls.h"

#include <algorithm>

#include "mvw/core/GlyphDefaults.h"
#include "mvw/render/GlyphMap.h"

namespace mvw::viewer {

double glyphSpacingMm(const render::RenderSettings& v) {
  return render::blueNoiseSpacing(v.glyphMap.size) * v.glyphDiameterMm / v.glyphMap.diameter;
}

void setGlyphSpacingMm(render::RenderSettings& v, double spacingMm) {
  v.glyphDiameterMm = kBlueNoiseDiameterFraction * spacingMm;
  v.glyphMap = render::blueNoiseGlyphMap(spacingMm, v.glyphDiameterMm, v.glyphMap.seed);
}

ValueWindow functionalWindow(const render::RenderSettings& v, std::pair<double, double> range) {
  return v.functionalWindow.orRange(range.first, range.second);
}

void setFunctionalWindow(render::RenderSettings& v, double low, double high,
                         std::pair<double, double> range) {
  v.functionalWindow = {low, std::max(high, low + 1e-6 * (range.second - range.first))};
}

}  // namespace mvw::viewer
