#include "GlyphIcons.h"

#include <cmath>

#include "mvw/core/Volume.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render::detail {

namespace {
constexpr int kHalf = 16;  // voxels either side of the glyph's centre
}

GlyphIcons::GlyphIcons() = default;
GlyphIcons::~GlyphIcons() = default;

void GlyphIcons::fill(GlContext& context, const RenderSettings& view, GlyphLegend& legend,
                      int pixels) {
  bool any = false;
  for (const GlyphLegendEntry& e : legend.entries) any |= e.value.has_value() && e.size > 0.0;
  if (!any || !view.glyphs.on) return;
  const GlyphMapSettings& g = view.glyphMap;
  if (!renderer_ || g.size != map_.size || g.count != map_.count || g.diameter != map_.diameter ||
      g.seed != map_.seed || g.placement != map_.placement || view.glyphDiameterMm != diameterMm_) {
    // The plane: tissue (1) behind y = the first glyph's centre (posterior), air (0) in front,
    // so the isosurface at 0.5 passes through the centre facing an anterior camera; the grid
    // spans 1.6 glyph radii either side.
    const GlyphMap map = makeGlyphMap(g, /*texels=*/false);
    const double voxelsPerMm = g.diameter / view.glyphDiameterMm;
    const glm::dmat3 glyphFromWorld = voxelsPerMm * glyphMapRotation(g.placement);
    const glm::dvec3 centre = glm::inverse(glyphFromWorld) * map.centres.at(0);
    const double voxel = 1.6 * 0.5 * view.glyphDiameterMm / kHalf;
    dims_ = glm::ivec3(2 * kHalf + 1, 2 * kHalf + 2, 2 * kHalf + 1);
    worldFromIndex_ = glm::dmat4(voxel);
    worldFromIndex_[3] = glm::dvec4(centre - voxel * glm::dvec3(kHalf, kHalf + 0.5, kHalf), 1.0);
    Volume plane(dims_, 1, ScalarType::Float32, worldFromIndex_);
    float* p = plane.dataAs<float>();
    for (int k = 0; k < dims_.z; ++k)
      for (int j = 0; j < dims_.y; ++j)
        for (int i = 0; i < dims_.x; ++i) *p++ = j > kHalf ? 1.0f : 0.0f;
    renderer_ = std::make_unique<VolumeRenderer>(context, plane);
    map_ = g;
    diameterMm_ = view.glyphDiameterMm;
  }
  RenderSettings s = view;
  s.mode = RenderMode::Isosurface;
  s.iso = 0.5;
  s.camera = CameraSettings{};
  s.camera.view = StandardView::Anterior;
  s.camera.zoom = std::sqrt(3.0) * 0.95;
  s.size = {pixels, pixels};
  s.crop = Crop{};
  s.overlay.fusion = false;
  s.jitter = false;
  s.stepMm = 0.0;
  if (legend.high > legend.low) s.functionalWindow = {legend.low, legend.high};
  for (GlyphLegendEntry& e : legend.entries) {
    if (!e.value || e.size <= 0.0) continue;
    Volume attribute(dims_, 1, ScalarType::Float32, worldFromIndex_);
    float* p = attribute.dataAs<float>();
    for (std::size_t i = 0; i < attribute.voxelCount(); ++i) p[i] = float(*e.value);
    if (s.glyphs.onSurface) {
      // Glyphs on the surface: their lattice is the image's, one centre in its middle (the
      // plane's middle, facing the camera); the attribute only under that glyph's disc, so the
      // icon is the one glyph whole, as a glyph of the image, not its neighbours' slivers.
      p = attribute.dataAs<float>();
      for (int k = 0; k < dims_.z; ++k)
        for (int j = 0; j < dims_.y; ++j)
          for (int i = 0; i < dims_.x; ++i, ++p)
            if (std::hypot(i - kHalf, k - kHalf) * worldFromIndex_[0][0] > 0.5 * diameterMm_)
              *p = 0.0f;
    }
    renderer_->setFunctional(attribute, glm::dmat4(1.0));
    e.icon = renderer_->render(s).image;
  }
  context.makeCurrent();
}

}  // namespace mvw::render::detail
