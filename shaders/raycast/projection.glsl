// What the projections share (projection.frag.glsl): the window, the ray's state and its
// emission. Each projection's accumulator (raycast/accumulate-mip.glsl, -minip, -average)
// and, fused, raycast/fusion-projection.glsl include this first.
#ifndef MVW_RAYCAST_PROJECTION
#define MVW_RAYCAST_PROJECTION
#include "raycast/common.glsl"
#include "common/colormap.glsl"
#include "common/functional.glsl"

uniform vec2 uWindowLevel;  // window width, level (centre), in the volume's unit

float emission(float v) {
  return clamp((v - (uWindowLevel.y - 0.5 * uWindowLevel.x)) / uWindowLevel.x, 0.0, 1.0);
}

struct RayState {
  float value;
  float depth;
  int count;
  float bound;  // MIP: the ray's maximum is at least this (RAY_PREPASS)
  // Depth cue, per ray: beta(t) = cue0 - cue1 t (eq. 3 with z' = a z + b) and the emission
  // phi = clamp(v * scale + offset): the loop then multiplies and adds, and never divides
  // (a division per sample cost the cue a third of plain MIP's time on llvmpipe).
  // Without the cue (startProjection: noCue) 1, 0, 1, 0.
  float cue0, cue1, scale, offset;
#if defined(MVW_FUSION)
  // The functional projection (fusion-projection.glsl): the largest (cued) fraction above the
  // threshold, -1 for none; with MVW_FUSION_MEAN the sum of the fractions over fusedCount
  // samples inside the volume.
  float fused;
  int fusedCount;
  // The ray in the functional volume's texture coordinates (uFunctionalFromWorld is affine):
  // sample t lies at fusedOrigin + t fusedDir, one multiply-add per sample, not a matrix.
  vec3 fusedOrigin, fusedDir;
#endif
};

void noCue(inout RayState s) {
  s.cue0 = 1.0;
  s.cue1 = 0.0;
  s.scale = 1.0;
  s.offset = 0.0;
}

#endif
