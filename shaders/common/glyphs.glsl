// Volumetric normal glyphs (Seipel 2007): the shading normal of the anatomy is perturbed by
// spherical normal glyphs from a periodic normal map, weighted by the functional attribute
// beta at the sample, so bumps (or dimples) appear where the attribute is.
#ifndef MVW_COMMON_GLYPHS
#define MVW_COMMON_GLYPHS

#include "common/functional.glsl"

uniform bool uGlyphs;
uniform sampler3D uGlyphMap;   // RGBA16F, repeats: RGB glyph normal, A distance / radius (-1 outside)
uniform float uGlyphPeriod;    // world mm covered by one period of the map (axis-aligned)
uniform int uGlyphMethod;      // 0: simple blending, eq. (1); 1: size and convexity control, eqs. (2)-(3)
uniform int uGlyphConvexity;   // 0: convex bumps, 1: concave dimples, 2: both (attribute below the
                               //    middle of its range: dimples, above: bumps)

// nO: the unit outward surface normal of the anatomy at `world`.
vec3 glyphNormal(vec3 world, vec3 nO) {
  float u = functionalFraction(world);
  float beta = uGlyphConvexity == 2 ? 2.0 * u - 1.0 : u;
  if (beta == 0.0) return nO;  // no attribute: the anatomy's own normal, bit for bit
  vec4 g = textureLod(uGlyphMap, world / uGlyphPeriod, 0.0);
  if (g.a < 0.0) return nO;    // outside every glyph
  vec3 nG = normalize(g.rgb);
  if (uGlyphMethod == 0) return normalize(nO + beta * nG);  // eq. (1): N = N_O + beta N_G
  float cosAlpha = dot(nO, nG);                              // eq. (3): alpha = acos(N_O . N_G)
  if (cosAlpha <= 0.0) return nO;  // the glyph's far hemisphere does not face this surface
  float d = g.a * sqrt(max(0.0, 1.0 - cosAlpha * cosAlpha));  // eq. (2): d = r sin(alpha)
  if (d > abs(beta)) return nO;    // denied: the apparent bump radius is |beta| glyph radii
  bool concave = uGlyphConvexity == 1 || (uGlyphConvexity == 2 && beta < 0.0);
  // A dimple is the bump mirrored about the surface normal.
  return concave ? normalize(2.0 * cosAlpha * nO - nG) : nG;
}

#endif
