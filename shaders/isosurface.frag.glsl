// Isosurface ray casting: the first step that crosses uIsoValue is refined by bisection
// (8 halvings: 1/256 of a step), then shaded with Phong from the gradient at the hit.
// With glyphs, common/glyphs.glsl and with the cut face raycast/cutface.glsl come first
// (RaycastFeatures.cpp).
#include "raycast/common.glsl"
#include "common/functional.glsl"

uniform float uIsoValue;
uniform vec4 uIsoColor;

struct RayState {
  float hitT;
};

void setupHook(inout RayState s, Ray ray) { s.hitT = -1.0; }

// A block whose values all lie below the isovalue holds no crossing: skip it. The grid point
// one step back is then a skipped sample, and below the surface too.
bool skipHook(RayState s, float t, vec3 tex) { return blockRange(tex).y < uIsoValue; }

bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  if (value < uIsoValue) return true;
  // The previous grid point (sampled or skipped) lies below the surface, or the ray entered
  // within this step: bisect between.
  s.hitT = isoCrossing(ray, max(t - uStep, gRayEntry), t, uIsoValue);
  return false;
}

void finishHook(inout RayState s, Ray ray, vec2 span) {
  if (s.hitT < 0.0) {
    fragColor = vec4(uBackground, 1.0);
    fragDepth = -1.0;
    return;
  }
  vec3 hit = ray.origin + s.hitT * ray.dir;
  vec4 g = sampleGradient(toTexture(hit));
  float magnitude = length(g.xyz);
  vec3 n = magnitude > 1e-6 ? -g.xyz / magnitude : -ray.dir;
  // Where the ray enters the (cropped) box already inside the surface, the visible surface
  // is the cut face itself: shade it flat, facing the viewer, not with the gradient of
  // whatever tissue was cut (noise, for a CT).
  if (s.hitT <= gRayEntry) n = -ray.dir;
#if defined(MVW_CUT_FACE)
  // The anatomy's grey under the window instead of the isosurface colour (cutface.glsl).
  if (s.hitT <= gRayEntry) {
    fragColor = vec4(cutFaceColour(hit, ray.dir, sampleValue(toTexture(hit)), g.a, true), 1.0);
    fragDepth = s.hitT;
    return;
  }
#endif
#if defined(MVW_GLYPH_KINDS)
  gGlyphSurfaceValue = uIsoValue;  // glyphs on the surface: where the centre's ray meets it
#endif
#if defined(MVW_GLYPHS)
  n = glyphNormal(hit, n, g.a);
#endif
  vec3 colour = uHasFunctional ? fuseColour(uIsoColor.rgb, hit) : uIsoColor.rgb;  // colour fusion
  fragColor = vec4(phong(colour, n, ray.dir), 1.0);
  fragDepth = s.hitT;
}

#include "raycast/template.glsl"
