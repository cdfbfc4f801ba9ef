// Volumetric normal glyphs (Seipel 2007): the shading normal of the anatomy is perturbed by
// spherical normal glyphs from a periodic normal map, weighted by the functional attribute
// beta at the sample, so bumps (or dimples) appear where the attribute is.
#ifndef MVW_COMMON_GLYPHS
#define MVW_COMMON_GLYPHS

#include "common/functional.glsl"

uniform sampler3D uGlyphMap;   // RGBA8, repeats: RGB = (normal + 1) / 2, A = 0 outside a glyph, else
                               // (1 + 254 distance / radius) / 255 (8 bits: the cheap texture
                               // path of a software rasteriser; glyph shading stays under 25 %)
uniform float uGlyphPeriod;    // world mm covered by one period of the map (axis-aligned)
// Method and convexity are compile-time variants, like every feature switch in the ray loop:
// MVW_GLYPH_SIMPLE: simple blending, eq. (1) (default: size and convexity control, eqs. 2-3);
// MVW_GLYPH_CONCAVE: dimples; MVW_GLYPH_BOTH: dimples below the middle of the attribute's
// range, bumps above (default: convex bumps).

// nO: the unit outward surface normal of the anatomy at `world`.
vec3 glyphNormal(vec3 world, vec3 nO) {
  // The glyph map first: most samples lie outside every glyph and need no attribute.
  vec4 g = textureLod(uGlyphMap, world / uGlyphPeriod, 0.0);
  if (g.a == 0.0) return nO;   // outside every glyph
  g.a = (g.a * 255.0 - 1.0) / 254.0;  // distance / radius
  g.rgb = g.rgb * 2.0 - 1.0;
  float u = functionalFraction(world);
#if defined(MVW_GLYPH_BOTH)
  float beta = 2.0 * u - 1.0;
#else
  float beta = u;
#endif
  if (beta == 0.0) return nO;  // no attribute: the anatomy's own normal, bit for bit
  vec3 nG = normalize(g.rgb);
#if defined(MVW_GLYPH_SIMPLE)
  return normalize(nO + beta * nG);  // eq. (1): N = N_O + beta N_G
#else
  float cosAlpha = dot(nO, nG);                              // eq. (3): alpha = acos(N_O . N_G)
  if (cosAlpha <= 0.0) return nO;  // the glyph's far hemisphere does not face this surface
  float d = g.a * sqrt(max(0.0, 1.0 - cosAlpha * cosAlpha));  // eq. (2): d = r sin(alpha)
  if (d > abs(beta)) return nO;    // denied: the apparent bump radius is |beta| glyph radii
  // A dimple is the bump mirrored about the surface normal.
#if defined(MVW_GLYPH_CONCAVE)
  return normalize(2.0 * cosAlpha * nO - nG);
#elif defined(MVW_GLYPH_BOTH)
  return beta < 0.0 ? normalize(2.0 * cosAlpha * nO - nG) : nG;
#else
  return nG;
#endif
#endif
}

#endif
