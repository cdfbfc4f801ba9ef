#pragma once
// How volumetric normal glyphs (Seipel 2007) are drawn: one value for the study config's view
// ("glyphs": {...}, config::ViewConfig) and the renderer (render::RenderSettings), so planning
// a view moves it whole. Its keys, ranges and defaults: the config's glyph style table
// (modules/config, docs/config-reference.md); the defaults' one home is mvw/core/GlyphDefaults.h.
//
// Not here, because each side holds its own form of them:
// - where the glyphs sit: the config asks for a placement, spacing, diameter and the paper
//   map's count, size and seed; the renderer holds the map that makes (glyphDiameterMm and
//   render::GlyphMapSettings). study::planViews and study::describeView (ViewPlan.cpp) are the
//   one conversion pair.
// - the chosen labels: the config names them (numbers or the atlas's names), the renderer holds
//   the numbers the label table gives (study's chosenLabels).
// - render::RenderSettings::glyphLayerMm: a renderer prototype with no config key yet.
#include <vector>

#include "mvw/core/GlyphDefaults.h"
#include "mvw/core/RenderMode.h"

namespace mvw {

// Size control by eqs. (2)-(3) of Seipel 2007 (sized), or eq. (1) blending (simple).
// Config names: sized, simple.
enum class GlyphMethod { Sized, Simple };

struct GlyphStyle {
  // Composite and isosurface: glyphs drawn (the view's "glyphs" object is present). Needs a
  // functional volume.
  bool on = false;
  GlyphMethod method = GlyphMethod::Sized;
  GlyphConvexity convexity = GlyphConvexity::Bumps;
  // The apparent bump radius just above the attribute window's low end, in glyph radii; it
  // grows linearly to 1 at the high end (shaders/common/glyphs.glsl).
  double minSize = kGlyphMinSize;
  // Composite DVR (beyond the paper): the least opacity per mm of ray a bump gives the samples
  // it tilts, so bumps show in translucent tissue.
  double dvrOpacity = kGlyphDvrOpacityPerMm;
  // Glyph kinds (issue 52): the glyphs on the visible surface, a hexagonal lattice on the image
  // (each glyph's radius the glyph diameter's half, in pixels at the view's scale; orthographic
  // views only, a perspective view keeps the 3D lattice), each shape laid out on the disc that
  // faces the viewer, instead of the 3D lattice that the surface cuts at random depths
  // (shaders/common/glyphs.glsl: glyphScreenNormal). The glyphs keep to the image, not to the
  // anatomy, when the view turns.
  bool onSurface = false;
  // Glyph kinds for classes (issue 40): with functional classes, class c (labels) takes
  // classKinds[c] (the last one past the end); without, the attribute window is cut into
  // classKinds.size() equal ranges, range c of kind c (an ordinal attribute in classes).
  // Empty: bumps (and the convexity) as before.
  std::vector<GlyphKind> classKinds;
  bool operator==(const GlyphStyle&) const = default;
};

}  // namespace mvw
