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

// Volumetric normal glyphs (Seipel 2007): convex bumps, concave dimples, or both (dimples
// below the attribute window's middle, bumps above). Config names: convex, concave, both.
enum class GlyphConvexity { Bumps, Dimples, Both };

}  // namespace mvw
