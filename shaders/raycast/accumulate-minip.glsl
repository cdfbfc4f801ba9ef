// MinIP's accumulator (projection.frag.glsl; RaycastPrograms pastes it for minip): the
// minimum, ties keeping the sample nearest the viewer. Defines what accumulate-mip.glsl does.
#ifndef MVW_ACCUMULATE_MINIP
#define MVW_ACCUMULATE_MINIP
#include "raycast/projection.glsl"

void startProjection(inout RayState s, Ray ray) {
  noCue(s);
  s.value = 3.4e38;
}

float cued(RayState s, float t, float phi) { return phi; }  // no depth cue

// A block whose minimum cannot go below the ray's minimum so far changes nothing (r: its range).
#define PROJECTION_SETTLES
bool anatomySettled(RayState s, float t, vec2 r) { return r.x >= s.value; }

void anatomySample(inout RayState s, float t, float value) {
  if (value < s.value) { s.value = value; s.depth = t; }
  s.count++;
}

float projectionGrey(RayState s) { return emission(s.value); }

#endif
