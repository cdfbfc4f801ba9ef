// Projections with window/level: MIP (maximum; ties keep the sample nearest the viewer),
// MinIP (minimum) and average intensity (X-ray-like). What the samples make of the ray is the
// mode's accumulator (raycast/accumulate-mip.glsl, -minip, -average), and a fused projection's
// functional part raycast/fusion-projection.glsl: RaycastPrograms pastes both before this file
// (the mode's, and the fusion feature's include, RaycastFeatures.cpp). This file is what they
// share: the hooks the template calls.
#include "raycast/projection.glsl"

void setupHook(inout RayState s, Ray ray) {
  startProjection(s, ray);
  s.depth = -1.0;
  s.count = 0;
  s.bound = s.value;
#if defined(MVW_FUSION)
  startFusion(s, ray);
#endif
}

#if !defined(MVW_FUSION)
// Empty-space skipping by the block min/max grid (one-voxel apron, so no trilinear sample in a
// block leaves its range): the accumulator's anatomySettled says whether a block of that range
// can change the projection (fused: fusion-projection.glsl's own, both volumes').
// With PROJECTION_LEVELS (plain MIP) the block's texel also says how many blocks around it a
// settled ray steps over at once (settledReach).
#if defined(PROJECTION_LEVELS)
bool skipHook(RayState s, float t, vec3 tex) {
  vec4 r = texelFetch(uBlockRange, blockOf(tex), 0);  // max, then the levels' distances
  gSkipReach = settledReach(r.yzw);
  return anatomySettled(s, t, vec2(0.0, r.x));
}
#else
bool skipHook(RayState s, float t, vec3 tex) { return anatomySettled(s, t, blockRange(tex)); }
#endif

bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  anatomySample(s, t, value);
  return true;
}
#endif

void finishHook(inout RayState s, Ray ray, vec2 span) {
  if (s.count == 0) {
    fragColor = vec4(backgroundColour(uBackground), 1.0);
    fragDepth = -1.0;
    return;
  }
  vec3 colour = imageColour(projectionGrey(s));
#if defined(MVW_FUSION)
  colour = fuseProjection(s, colour);
#endif
  fragColor = vec4(colour, 1.0);
  fragDepth = s.depth;
}

#include "raycast/template.glsl"
