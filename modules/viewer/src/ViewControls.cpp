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

std::pair<double, double> functionalWindow(const render::RenderSettings& v,
                                           std::pair<double, double> range) {
  if (v.functionalHigh > v.functionalLow) return {v.functionalLow, v.functionalHigh};
  return range;
}

void setFunctionalWindow(render::RenderSettings& v, double low, double high,
                         std::pair<double, double> range) {
  v.functionalLow = low;
  v.functionalHigh = std::max(high, low + 1e-6 * (range.second - range.first));
}

}  // namespace mvw::viewer
