// Composite DVR: a transfer function over value (1D) or over value x gradient magnitude
// (2D), its opacity already corrected for the step on the CPU; front-to-back compositing
// with associated (opacity-weighted) colours, early ray termination at 0.99, optional
// Phong shading from the precomputed gradient.
// With glyphs, common/glyphs.glsl and with the cut face raycast/cutface.glsl come first
// (RaycastFeatures.cpp).
#include "raycast/common.glsl"
#include "common/functional.glsl"

uniform sampler2D uTransfer;   // RGBA over (value, |gradient| * uGradientScale); alpha per step
uniform vec2 uTransferRange;   // (scale, offset): value * scale + offset is the table's column, 0..1
                               // (a multiply-add per sample, not a division), entry i's value at
                               // its texel centre
uniform float uGradientScale;  // 1 / the |gradient| (unit/mm) at the last row
uniform vec2 uGradientRows;    // 0..1 (first to last row) * x + y: the rows' texel centres
uniform vec2 uVisibleValues;   // values outside [x, y] are transparent whatever the gradient
uniform bool uShading;

struct RayState {
  vec4 color;   // associated colour, alpha
  float depth;  // distance where the opacity first passed 0.5
#if defined(MVW_GLYPH_KINDS)
  float glyphStart;  // the ray's first sample that ran the glyph code (uGlyphLayerMm > 0)
#endif
};

void setupHook(inout RayState s, Ray ray) {
  s.color = vec4(0.0);
  s.depth = -1.0;
#if defined(MVW_GLYPH_KINDS)
  s.glyphStart = -1.0;
#endif
}

bool skipHook(RayState s, float t, vec3 tex) { return !blockVisible(tex); }

// One sample: kRayGoOn, kRayEnd (early termination), or kRayHandOver (only with glyphs =
// false): this sample needs the glyph code, nothing is composited, and the ray goes on from
// this sample in the full loop, which runs it (RAY_MIDDLE_LOOP below).
int compositeSample(inout RayState s, float t, vec3 tex, float value, Ray ray, const bool glyphs) {
  float u = clamp(value * uTransferRange.x + uTransferRange.y, 0.0, 1.0);
  vec4 g = vec4(0.0);
  vec4 c;
  // Variants are compile-time (#define from C++): as uniform branches the unused features
  // cost this loop half its speed on llvmpipe.
#if defined(MVW_TF2D)
  g = sampleGradientOfValue(tex);
  float row = clamp(length(g.xyz) * uGradientScale, 0.0, 1.0) * uGradientRows.x + uGradientRows.y;
  c = textureLod(uTransfer, vec2(u, row), 0.0);
#else
  c = textureLod(uTransfer, vec2(u, 0.5), 0.0);
#endif
  if (c.a <= 0.0) return kRayGoOn;
  float alpha = c.a;
  vec3 rgb = c.rgb;
#if defined(MVW_FUSION)
  rgb = fuseColour(rgb, ray.origin + t * ray.dir);  // colour fusion
#endif
  if (uShading) {
#if !defined(MVW_TF2D)
    g = sampleGradientOfValue(tex);
#endif
    float magnitude2 = dot(g.xyz, g.xyz);
    if (magnitude2 > 1e-12) {
      vec3 n = -g.xyz * inversesqrt(magnitude2);
#if defined(MVW_GLYPHS)
      // A sample that adds less than one grey level to the pixel cannot show a glyph. The
      // attribute comes with the gradient (its alpha): no second volume is read per sample.
      // Below the window (g.a = 0) the glyph code is skipped outright: where a whole block of
      // samples lies there, a software rasteriser need not run it at all.
      // Beyond the paper (not in its own placement): a sample a bump tilts gets at least
      // uGlyphAlpha (GlyphDefaults.h: kGlyphDvrOpacityPerMm per step), so in translucent
      // tissue the bump is shaded like a small surface instead of a few grey levels' change.
#if defined(MVW_GLYPH_PAPER)
      const float glyphAlpha = 0.0;
#else
      const float glyphAlpha = uGlyphAlpha;
#endif
      if (g.a > 0.0 && (1.0 - s.color.a) * max(alpha, glyphAlpha) > 1.0 / 255.0) {
        if (!glyphs) return kRayHandOver;
#if defined(MVW_GLYPH_KINDS)
        if (uGlyphLayerMm > 0.0) {
          if (s.glyphStart < 0.0) s.glyphStart = t;
          gGlyphMaxDepth = s.glyphStart + uGlyphLayerMm - t;
        }
#endif
        vec3 bumped = glyphNormalMapped(uGlyphFromWorld * (ray.origin + t * ray.dir), n, -ray.dir, g.a);
        if (bumped != n) alpha = max(alpha, glyphAlpha);
        n = bumped;
      }
#endif
      rgb = phong(rgb, n, ray.dir);
    }
  }
  s.color.rgb += (1.0 - s.color.a) * alpha * rgb;
  s.color.a += (1.0 - s.color.a) * alpha;
  if (s.depth < 0.0 && s.color.a >= 0.5) s.depth = t;
  return s.color.a < 0.99 ? kRayGoOn : kRayEnd;
}

bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  return compositeSample(s, t, tex, value, ray, true) == kRayGoOn;
}

#if defined(MVW_GLYPHS)
// The ray runs without the glyph code until its first sample that needs it, then with it
// (RAY_MIDDLE_LOOP, then the full loop), and the glyph map position is computed per sample in
// that last loop only: carried through one loop as ray state (six floats), the glyph ray cost
// composite DVR 1.35x the frame without glyphs on llvmpipe even with no attribute in view
// (register pressure in every iteration); split, 1.07x then
// (docs/performance-log.md#glyph-split-loop). Since plain composite got the hand-back, glyph
// composite measures 1.26-1.31x over it (docs/performance.md#what-the-methods-cost). The
// pixels are the same, bit for bit: below the window the glyph code returns the anatomy's
// normal. Before both, the lean loop (below) passes the transparent samples, and both hand the
// ray back to it at the next one.
#define RAY_MIDDLE_LOOP
int middleSampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  return compositeSample(s, t, tex, value, ray, false);
}
#endif
// The ray runs a lean loop up to its first sample the table does not leave transparent, then
// the full one from that sample on (RAY_LEAN_LOOP): the lean loop reads the value alone and
// asks whether it lies between the first and the last table entry with some opacity (no table
// lookup), without the gradient, the shading and the compositing. llvmpipe runs every
// part of a loop body on every iteration, and most samples in a visible block are transparent
// (the air and soft tissue in front of the bone), so they no longer pay for the rest. The
// samples and their order are the same, and a sample handed over early only costs time: the
// pixels are the same too. The 2D table's opacity is the 1D one times a factor of at most 1,
// so the 1D table's entries answer for it. The value comes from the intensity texture alone
// (one channel; the packed texture's A holds the same texel).
// The full loop hands the ray back to the lean one at its next sample outside those values
// (RAY_HAND_BACK): behind a thin bone most samples are transparent (on the Cranium CT's bone
// preset more than half of the full loop's), and in the lean loop they cost a one-channel
// fetch and a comparison instead of the packed fetch, the table, the shading and the
// compositing. The same samples, the same pixels.
#define RAY_LEAN_LOOP
#define RAY_HAND_BACK
bool handBackHook(float value) { return value < uVisibleValues.x || value > uVisibleValues.y; }
float leanSampleValue(vec3 tex) {
  return textureLod(uIntensity, storedTexture(tex), 0.0).r * uValueMapping.x + uValueMapping.y;
}
int leanSampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  return value >= uVisibleValues.x && value <= uVisibleValues.y ? kRayHandOver : kRayGoOn;
}

#if defined(MVW_CUT_FACE)
// A ray that enters the cropped box where the table shows the tissue meets the crop's cut
// face: opaque, the anatomy's grey under the window with fusion and glyphs on it
// (cutface.glsl), and nothing behind it. Elsewhere the ray runs as without the variant.
#define RAY_ENTRY_HOOK
bool entryHook(inout RayState s, Ray ray, vec2 span) {
  vec3 tex = textureAt(span.x);
  float value = sampleValue(tex);
  if (value < uVisibleValues.x || value > uVisibleValues.y) return true;
  float beta = 0.0;
#if defined(MVW_GLYPHS)
  beta = sampleGradientOfValue(tex).a;
#endif
  vec3 face = ray.origin + span.x * ray.dir;
  s.color = vec4(cutFaceColour(face, ray.dir, value, beta, uShading), 1.0);
  s.depth = span.x;
  return false;
}
#endif

void finishHook(inout RayState s, Ray ray, vec2 span) {
  fragColor = vec4(s.color.rgb + (1.0 - s.color.a) * uBackground, 1.0);
  fragDepth = s.depth;
}

#include "raycast/template.glsl"
