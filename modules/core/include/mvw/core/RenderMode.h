#pragma once
// The render modes, the shared vocabulary of the study config and the renderer.
// ShellMip, ShellSum, ShellLit: the paper's own discrete algorithm (Heidrich et al. 1995):
// isosurface shells at n emission thresholds drawn as triangles, the GL depth test doing the
// maximum (eq. 4), approximate summation (section 2.4), or lit shells.
#include <optional>
#include <string>
#include <vector>

namespace mvw {

enum class RenderMode {
  Composite,
  Isosurface,
  Mip,
  MinIp,
  Average,
  Mpr,
  ShellMip,
  ShellSum,
  ShellLit
};

// The names the config and the command line use: composite, isosurface, mip, minip, average,
// mpr, shells-mip, shells-sum, shells-lit.
std::optional<RenderMode> parseRenderMode(const std::string& name);
std::string toString(RenderMode mode);
std::vector<std::string> renderModeNames();

// The paper's discrete modes (isosurface shells drawn as triangles, not ray cast).
bool isShellMode(RenderMode mode);

// The projections: mip, minip and average (one value per ray, shaders/projection.frag.glsl).
bool isProjectionMode(RenderMode mode);

// Whether a mode can blend the functional volume in (colour fusion): composite and isosurface
// colour the anatomy where they sample it; mip, minip and average lay the functional volume's
// own projection along each ray over the anatomy's. MPR shows it as its overlay instead; the
// shell modes draw isosurface triangles of the anatomy alone and cannot.
bool takesFusion(RenderMode mode);

// A fused minip or average view's functional projection along each ray: the maximum of its
// samples or their mean (a fused MIP always takes the maximum). Config names: max, mean.
enum class FusionProjection { Max, Mean };
// The modes a fused view of which may take the mean (minip, average: fusion_projection).
bool takesFusionMean(RenderMode mode);

// What the opaque face shows where a crop cuts an isosurface or a composite rendering (issue 36
// item 7): the anatomy's grey values under the window as an MPR on that plane would show them,
// the glyphs and fusion on top (anatomy), or the isosurface colour / the transfer function as
// before (plain). Config names: anatomy, plain.
enum class CutFace { Anatomy, Plain };
// The modes whose crop leaves a cut face: composite and isosurface.
bool hasCutFace(RenderMode mode);

// Volumetric normal glyphs (Seipel 2007): convex bumps, concave dimples, or both (dimples
// below the attribute window's middle, bumps above). Config names: convex, concave, both.
enum class GlyphConvexity { Bumps, Dimples, Both };

// The shapes a glyph can take (issue 40: a nominal attribute's classes told apart by shape),
// each a normal-map glyph (the shading normal perturbed, no geometry): bumps (hemispheres),
// dimples (bumps inverted), rings (a torus with a flat centre), ridges (a bar across the glyph,
// running along the patient's S axis where the surface allows, else L), cones (a peak with
// concave flanks: a dark point fading to a light rim), crosses (two bars at right angles).
// Config names: the plurals.
enum class GlyphKind { Bumps, Dimples, Rings, Ridges, Cones, Crosses };
inline constexpr int kGlyphKindCount = 6;
inline const char* glyphKindName(GlyphKind k) {
  constexpr const char* names[] = {"bumps", "dimples", "rings", "ridges", "cones", "crosses"};
  return names[static_cast<int>(k)];
}
inline std::optional<GlyphKind> parseGlyphKind(const std::string& name) {
  for (int i = 0; i < kGlyphKindCount; ++i)
    if (name == glyphKindName(static_cast<GlyphKind>(i))) return static_cast<GlyphKind>(i);
  return std::nullopt;
}

}  // namespace mvw
