// Average intensity's accumulator (projection.frag.glsl; RaycastPrograms pastes it for
// average): the mean of the ray's samples, X-ray-like. Defines what accumulate-mip.glsl does
// but PROJECTION_SETTLES: every sample changes the sum, so no block is skipped.
#ifndef MVW_ACCUMULATE_AVERAGE
#define MVW_ACCUMULATE_AVERAGE
#include "raycast/projection.glsl"

void startProjection(inout RayState s, Ray ray) {
  noCue(s);
  s.value = 0.0;
}

float cued(RayState s, float t, float phi) { return phi; }  // no depth cue

bool anatomySettled(RayState s, float t, vec2 r) { return false; }

void anatomySample(inout RayState s, float t, float value) {
  s.value += value;
  s.count++;
}

float projectionGrey(RayState s) {
  float v = s.value;
  v /= float(s.count);
  return emission(v);
}

#endif
