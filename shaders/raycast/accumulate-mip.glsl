// MIP's accumulator (projection.frag.glsl; RaycastPrograms pastes it for mip): the maximum,
// ties keeping the sample nearest the viewer; with the depth cue (MVW_DEPTH_CUE) the cued
// emission's maximum. Defines startProjection, cued, anatomySettled, anatomySample and
// projectionGrey, and PROJECTION_SETTLES (a block can leave the projection as it is).
#ifndef MVW_ACCUMULATE_MIP
#define MVW_ACCUMULATE_MIP
#include "raycast/projection.glsl"

// Depth-cued maximum projection (Heidrich, McCool and Stevens 1995). Emission phi is the
// windowed value in 0..1; z runs along the projector from 0 at the background (the far side of
// the bounding sphere) to 1 at the image side. The ramp beta(z') = beta0 + beta_m z' with
// z' = a z + b (section 2.3, beta_m = 1) multiplies phi BEFORE the maximum (eq. 3), so a dim
// near structure can beat a brighter far one; a = 0, b = 1, beta0 = 0 is plain MIP.
// A compile-time variant (MVW_DEPTH_CUE): as a uniform branch it cost plain MIP 60 % on
// llvmpipe even when off.
uniform vec3 uCue;             // beta0 (brightness), a (depth cue amount), b (contrast)
uniform vec4 uBoundingSphere;  // centre (world mm), radius

void startProjection(inout RayState s, Ray ray) {
#if defined(MVW_DEPTH_CUE)
  // z = 1 - (t - tFront) / 2R, so beta0 + a z + b = cue0 + uCueSlope t with one dot per ray.
  float tFront = dot(uBoundingSphere.xyz - ray.origin, ray.dir) - uBoundingSphere.w;
  s.cue0 = uCue.x + uCue.z + uCue.y * (1.0 + tFront / (2.0 * uBoundingSphere.w));
  s.cue1 = uCue.y / (2.0 * uBoundingSphere.w);
  s.scale = 1.0 / uWindowLevel.x;
  s.offset = 0.5 - uWindowLevel.y / uWindowLevel.x;
#else
  noCue(s);
#endif
  s.value = -3.4e38;
}

// A fraction phi at the ray's sample t under the cue: eq. (3), beta(z') phi(z), before the
// maximum (the fused projection's too).
float cued(RayState s, float t, float phi) {
#if defined(MVW_DEPTH_CUE)
  phi *= max(s.cue0 - s.cue1 * t, 0.0);
#endif
  return phi;
}

// Several settled blocks at once (plain MIP; projection.frag.glsl's skipHook): uMipLevels are
// three rising levels of the block maxima, and the block's texel (BlockGrid::prepareMipLevels)
// holds its maximum and, for each level, the Chebyshev distance d in blocks to the nearest
// block whose maximum is at or above it. Every block nearer than d has its maximum under the
// level; where the level is at or under the ray's pre-pass bound, those blocks are all settled
// (anatomySettled would skip each one by one), so a settled ray steps over the cube of d - 1
// blocks around its own. The samples the ray takes are the same, only fewer loop iterations
// reach them. Per ray (prepassHook), gLevelPick picks the highest level at or under the bound
// (all 0 where none is, and without the pre-pass): per sample a dot product, no decoding and
// no comparison. The texel's layout is plain MIP's (BlockGrid::mipRange), with or without
// the depth cue; a fused MIP reads its own grid (fusion-projection.glsl).
#define PROJECTION_LEVELS
uniform vec3 uMipLevels;
vec3 gLevelPick = vec3(0.0);
void pickLevel(float bound) {
  vec3 at = step(uMipLevels, vec3(bound));  // 1 for the levels at or under the bound (rising)
  gLevelPick = at - vec3(at.yz, 0.0);       // the highest of them alone
}
float settledReach(vec3 levelDistances) {
  return max(dot(levelDistances, gLevelPick) - 1.0, 0.0);
}

// Before the ray proper, every PREPASS_STRIDE-th of its samples: their maximum, less a
// margin, bounds the ray's maximum from below, so blocks whose maximum lies under it are
// skipped from the start. The maximum so far alone skips no block before the ray has met
// the brightest structure (in front of a skull: all of the air and the skin). The margin (a
// hundredth of the value range) is for safety only: the pre-pass reads the ray's own samples,
// their positions from the same functions (sampleDistance, textureAt), so no block that holds the
// ray's maximum, or a sample that ties with it, is skipped. (MinIP without it: its
// rays meet the air around a body first; with it, 2-5 % slower on the Cranium CT.) Not with
// nearest-neighbour sampling (MVW_NEAREST): were the compiler to evaluate the same expression
// differently in the two loops (a fused multiply-add in one only), a sample there could read
// another voxel altogether, which no margin short of the value range covers. A fused MIP
// bounds the anatomy's maximum alike, not the functional one's: a functional fetch on every
// 16th sample of every ray cost more than it saved on the few rays through a hot spot (the
// Cranium CT with its PET-like volume, docs/performance-log.md#fused-skipping).
#if !defined(MVW_DEPTH_CUE) && !defined(MVW_NEAREST)
#define RAY_PREPASS
#define PREPASS_STRIDE 16.0
void prepassHook(inout RayState s, float t0, float tEnd) {
  float m = s.value;
  for (float n = 0.0; n < float(uMaxSteps); n += PREPASS_STRIDE) {
    float t = sampleDistance(t0, n);  // the ray's own sample n
    if (t > tEnd) break;
    m = max(m, sampleValue(textureAt(t)));
  }
  s.bound = m - 0.01 * (uVolume.valueRange.y - uVolume.valueRange.x);
  pickLevel(s.bound);
}
#endif

// Empty-space skipping (projection.frag.glsl): a block whose maximum cannot beat the ray's
// maximum so far (with the depth cue, that maximum's emission under the cue at this sample,
// which only falls along the ray) holds no sample that changes the result; ties keep the first
// sample, so none is lost. r: the block's range.
#define PROJECTION_SETTLES
#if defined(MVW_DEPTH_CUE)
bool anatomySettled(RayState s, float t, vec2 r) {
  return max(s.cue0 - s.cue1 * t, 0.0) * clamp(r.y * s.scale + s.offset, 0.0, 1.0) <= s.value;
}
#else
bool anatomySettled(RayState s, float t, vec2 r) { return r.y <= s.value || r.y < s.bound; }
#endif

void anatomySample(inout RayState s, float t, float value) {
#if defined(MVW_DEPTH_CUE)
  value = (s.cue0 - s.cue1 * t) * clamp(value * s.scale + s.offset, 0.0, 1.0);  // eq. (3): beta(z') phi(z)
#endif
  // Strictly greater: of equally bright samples the first, nearest the viewer, wins.
  if (value > s.value) { s.value = value; s.depth = t; }
  s.count++;
}

float projectionGrey(RayState s) {
  float v = s.value;
  float grey = emission(v);
#if defined(MVW_DEPTH_CUE)
  // eq. (3): the background term beta0 Phi[0] competes in the maximum.
  grey = clamp(max(v, uCue.x * dot(uBackground, vec3(1.0 / 3.0))), 0.0, 1.0);
#endif
  return grey;
}

#endif
