#pragma once
// The functional volume in colour over the anatomy: one value for the study config's view
// (config::ViewConfig: "overlay", "fusion", "fusion_projection", "overlay_opacity",
// "overlay_threshold") and the renderer (render::RenderSettings), so planning a view moves it
// whole. The colour map is not here: the config names it (ColorMap), the renderer holds its
// table (study::applyColorMaps turns one into the other). Its keys, ranges and defaults: the
// config's overlay table (modules/config, docs/config-reference.md).
#include "mvw/core/RenderMode.h"

namespace mvw {

struct Overlay {
  // MPR views show the functional volume, where the renderer holds one.
  bool mpr = true;
  // Composite and isosurface: the colour map blended into the anatomy's colour before shading;
  // mip, minip and average: the functional volume's own projection along each ray in the
  // colour map over the anatomy's (takesFusion, mvw/core/RenderMode.h).
  bool fusion = false;
  // Fused minip and average: the functional projection, its maximum or mean along the ray.
  FusionProjection projection = FusionProjection::Max;
  double opacity = 0.5;
  double threshold = 0.25;  // fraction of the functional window below which nothing shows
  bool operator==(const Overlay&) const = default;
};

}  // namespace mvw
