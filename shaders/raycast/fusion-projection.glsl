// Colour fusion of a projection (MVW_FUSION with mip, minip or average; the fusion feature
// pastes it after the mode's accumulator, RaycastFeatures.cpp): over the anatomy's projection
// in its colour map, the functional volume's own projection along the same ray, in the
// overlay's colour map with its opacity (common/functional.glsl). One pass: the functional
// volume is sampled at the ray's very samples, through its own geometry and the registration
// (uFunctionalFromWorld), as composite's fusion samples it. Its projection is the maximum of
// its fractions above the overlay threshold (MIP always; minip and average by default), cued
// with the anatomy's depth cue (the accumulator's cued) before the maximum (a hot lesion in
// front reads brighter than one behind); or the mean of its fractions over the samples inside
// it, shown where the mean exceeds the threshold (MVW_FUSION_MEAN, minip and average). The
// fused program reads both volumes' ranges per block (uBlockRange bound to the fused grid,
// BlockGrid::setFunctional: RG the anatomy's, BA the functional's there) and skips a block
// only where neither projection can change; the plain ones read the anatomy's alone.
// Defines startFusion, skipHook, sampleHook and fuseProjection, and for the maximum the lean
// loop's hooks.
#ifndef MVW_FUSION_PROJECTION
#define MVW_FUSION_PROJECTION
#include "raycast/projection.glsl"

void startFusion(inout RayState s, Ray ray) {
#if defined(MVW_FUSION_MEAN)
  s.fused = 0.0;
#else
  s.fused = -1.0;
#endif
  s.fusedCount = 0;
  s.fusedOrigin = (uFunctionalFromWorld * vec4(ray.origin, 1.0)).xyz;
  s.fusedDir = (uFunctionalFromWorld * vec4(ray.dir, 0.0)).xyz;
}

#if defined(MVW_FUSION_MEAN)
// The mean reads every sample, and so its projection (average, minip) skips nothing.
bool skipHook(RayState s, float t, vec3 tex) { return false; }

void fuseSample(inout RayState s, float t, Ray ray) {
  bool inside;
  float u = overlayFractionAt(s.fusedOrigin + t * s.fusedDir, inside);
  if (inside) {
    s.fused += u;
    s.fusedCount++;
  }
}

vec3 fuseProjection(RayState s, vec3 colour) {
  float mean = s.fusedCount > 0 ? s.fused / float(s.fusedCount) : 0.0;
  if (s.fusedCount > 0 && mean > uOverlayThreshold) colour = blendOverlay(colour, mean);
  return colour;
}
#else
// The (cued) fraction the functional volume adds at the ray's sample t to the maximum, -1
// where none (outside its box, or at or under the threshold).
float fusedPhi(RayState s, float t) {
  bool inside;
  float u = overlayFractionAt(s.fusedOrigin + t * s.fusedDir, inside);
  if (!(inside && u > uOverlayThreshold)) return -1.0;  // a NaN too
  return cued(s, t, clamp(u, 0.0, 1.0));
}

// A fused projection's maximum: no functional sample in the block (its range r, the fused
// grid's BA) changes it where even the block's maximum, as fusedPhi would take it at this
// sample (fraction and cue fall monotonically with the value and along the ray), is at or
// under the threshold or the maximum so far. The functional volume's part of the test, and
// the state and sample it was made at, are kept for what follows in the loop (the lean loop's
// hand-over, the full loop's hand-back).
bool gFunctionalSettled;
RayState gState;
float gT;
bool skipHook(RayState s, float t, vec3 tex) {
  gState = s;
  gT = t;
  vec4 r = texelFetch(uBlockRange, blockOf(tex), 0);
  float u = (r.w - uFunctionalRange.x) / (uFunctionalRange.y - uFunctionalRange.x);
  float phi = cued(s, t, clamp(u, 0.0, 1.0));
  gFunctionalSettled = u <= uOverlayThreshold || phi <= s.fused;
  return anatomySettled(s, t, r.xy) && gFunctionalSettled;
}

void fuseSample(inout RayState s, float t, Ray ray) {
  s.fused = max(s.fused, fusedPhi(s, t));  // -1 (none) leaves it as it is
}

vec3 fuseProjection(RayState s, vec3 colour) {
  if (s.fused >= 0.0) colour = blendOverlay(colour, s.fused);
  return colour;
}

// A fused maximum's rays start in the lean loop, which reads the anatomy alone: llvmpipe runs
// the full loop's second fetch on every sample, skipped or not. A sample in a block where the
// functional volume cannot change the projection (skipHook just said so) is the anatomy's
// alone; the first elsewhere is handed over, and the full loop reads both from there on.
#define RAY_LEAN_LOOP
float leanSampleValue(vec3 tex) { return sampleValue(tex); }
int leanSampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  if (!gFunctionalSettled) return kRayHandOver;
  anatomySample(s, t, value);
  return kRayGoOn;
}
#if defined(PROJECTION_SETTLES)
// Past a hot spot, back to the lean loop at a sample that changes neither projection: the
// functional volume's settled in its block, and the anatomy's value is one its block test
// would have passed (average: every sample changes the sum, so no hand-back).
#define RAY_HAND_BACK
bool handBackHook(float value) {
  return gFunctionalSettled && anatomySettled(gState, gT, vec2(value));
}
#endif
#endif

// The functional volume at the ray's sample t, then the anatomy's.
bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  fuseSample(s, t, ray);
  anatomySample(s, t, value);
  return true;
}

#endif
