// Volumetric normal glyphs (Seipel 2007): the shading normal of the anatomy is perturbed by
// spherical normal glyphs from a periodic normal map, weighted by the functional attribute
// beta at the sample, so bumps (or dimples) appear where the attribute is.
#ifndef MVW_COMMON_GLYPHS
#define MVW_COMMON_GLYPHS

// The normal map in its compact form (modules/render GlyphMap): the map cut into cells, each
// naming the one glyph that reaches into it (0: none), and the glyph centres. N_G and A are
// evaluated from the centre exactly: what the RGBA map's texels hold, between texels too.
uniform usampler3D uGlyphCells;   // R8UI, repeats: 1 + glyph index, 0 = no glyph
layout(std140) uniform GlyphCentres {
  vec4 uGlyphCentres[255];        // map voxel coordinates
};
uniform float uGlyphVoxelsPerMm;  // map voxels per world mm (axis-aligned, periodic)
uniform float uGlyphMapSize;      // map voxels per period
uniform float uGlyphInvMapSize;   // 1 / uGlyphMapSize (the loop multiplies, never divides)
uniform float uGlyphRadius;       // map voxels
// Method and convexity are compile-time variants, like every feature switch in the ray loop:
// MVW_GLYPH_SIMPLE: simple blending, eq. (1) (default: size and convexity control, eqs. 2-3);
// MVW_GLYPH_CONCAVE: dimples; MVW_GLYPH_BOTH: dimples below the middle of the attribute's
// range, bumps above (default: convex bumps).

// nO: the unit outward surface normal of the anatomy at `world`; u: the functional attribute
// there, mapped to 0..1 (the gradient texture's alpha: see raycast/common.glsl).
// On a software rasteriser every line below runs for every sample (branches are masks, not
// jumps), so the tests are written without square roots or divisions where possible.
vec3 glyphNormal(vec3 world, vec3 nO, float u) {
#if defined(MVW_GLYPH_BOTH)
  float beta = 2.0 * u - 1.0;
#else
  float beta = u;
#endif
  if (beta == 0.0) return nO;  // no attribute: the anatomy's own normal, bit for bit
  vec3 p = world * uGlyphVoxelsPerMm;
  uint cell = textureLod(uGlyphCells, p * uGlyphInvMapSize, 0.0).r;
  if (cell == 0u) return nO;   // outside every glyph
  vec3 d = p - uGlyphCentres[cell - 1u].xyz;
  d -= uGlyphMapSize * round(d * uGlyphInvMapSize);  // the nearest periodic copy of the centre
  float d2 = dot(d, d);
  float r2 = uGlyphRadius * uGlyphRadius;
  if (d2 >= r2) return nO;     // A >= 1: outside the glyph
  vec3 nG = d * inversesqrt(max(d2, 1e-12));  // the glyph normal, away from its centre
#if defined(MVW_GLYPH_SIMPLE)
  return normalize(nO + beta * nG);  // eq. (1): N = N_O + beta N_G
#else
  float cosAlpha = dot(nO, nG);                              // eq. (3): alpha = acos(N_O . N_G)
  if (cosAlpha <= 0.0) return nO;  // the glyph's far hemisphere does not face this surface
  // eq. (2): d = r sin(alpha) with r = A = |d| / radius; denied where d > |beta| (the apparent
  // bump radius is |beta| glyph radii), compared squared.
  if (d2 * (1.0 - cosAlpha * cosAlpha) > beta * beta * r2) return nO;
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
