// Projections with window/level: MIP (maximum; ties keep the sample nearest the viewer),
// MinIP (minimum) and average intensity (X-ray-like). Chosen by MVW_MIP, MVW_MINIP or
// MVW_AVERAGE.
#include "raycast/common.glsl"
#include "common/colormap.glsl"
#include "common/functional.glsl"

// Colour fusion (MVW_FUSION): over the anatomy's projection in its colour map, the functional
// volume's own projection along the same ray, in the overlay's colour map with its opacity
// (common/functional.glsl). One pass: the functional volume is sampled at the ray's very
// samples, through its own geometry and the registration (uFunctionalFromWorld), as
// composite's fusion samples it. Its projection is the maximum of its fractions above the
// overlay threshold (MIP always; minip and average by default), depth-cued with the anatomy's
// cue, before the maximum (MVW_DEPTH_CUE: a hot lesion in front reads brighter than one
// behind); or the mean of its fractions over the samples inside it, shown where the mean
// exceeds the threshold (MVW_FUSION_MEAN, minip and average). A compile-time variant: the
// fused program reads both volumes' ranges per block (uBlockRange bound to the fused grid,
// BlockGrid::setFunctional: RG the anatomy's, BA the functional's there) and skips a block only
// where neither projection can change; the plain ones read the anatomy's alone.

uniform vec2 uWindowLevel;  // window width, level (centre), in the volume's unit

// Depth-cued maximum projection (Heidrich, McCool and Stevens 1995), MIP only. Emission
// phi is the windowed value in 0..1; z runs along the projector from 0 at the background
// (the far side of the bounding sphere) to 1 at the image side. The ramp
// beta(z') = beta0 + beta_m z' with z' = a z + b (section 2.3, beta_m = 1) multiplies phi
// BEFORE the maximum (eq. 3), so a dim near structure can beat a brighter far one;
// a = 0, b = 1, beta0 = 0 is plain MIP.
// A compile-time variant (MVW_DEPTH_CUE): as a uniform branch it cost plain MIP 60 % on
// llvmpipe even when off.
uniform vec3 uCue;          // beta0 (brightness), a (depth cue amount), b (contrast)
uniform vec4 uBoundingSphere;  // centre (world mm), radius

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
  float cue0, cue1, scale, offset;
#if defined(MVW_FUSION)
  // The functional projection: the largest (cued) fraction above the threshold, -1 for none;
  // with MVW_FUSION_MEAN the sum of the fractions over fusedCount samples inside the volume.
  float fused;
  int fusedCount;
  // The ray in the functional volume's texture coordinates (uFunctionalFromWorld is affine):
  // sample t lies at fusedOrigin + t fusedDir, one multiply-add per sample, not a matrix.
  vec3 fusedOrigin, fusedDir;
#endif
};

void setupHook(inout RayState s, Ray ray) {
#if defined(MVW_DEPTH_CUE)
  // z = 1 - (t - tFront) / 2R, so beta0 + a z + b = cue0 + uCueSlope t with one dot per ray.
  float tFront = dot(uBoundingSphere.xyz - ray.origin, ray.dir) - uBoundingSphere.w;
  s.cue0 = uCue.x + uCue.z + uCue.y * (1.0 + tFront / (2.0 * uBoundingSphere.w));
  s.cue1 = uCue.y / (2.0 * uBoundingSphere.w);
  s.scale = 1.0 / uWindowLevel.x;
  s.offset = 0.5 - uWindowLevel.y / uWindowLevel.x;
#else
  s.cue0 = 1.0;
  s.cue1 = 0.0;
  s.scale = 1.0;
  s.offset = 0.0;
#endif
#if defined(MVW_MINIP)
  s.value = 3.4e38;
#elif defined(MVW_MIP)
  s.value = -3.4e38;
#else
  s.value = 0.0;
#endif
  s.depth = -1.0;
  s.count = 0;
  s.bound = s.value;
#if defined(MVW_FUSION_MEAN)
  s.fused = 0.0;
#elif defined(MVW_FUSION)
  s.fused = -1.0;
#endif
#if defined(MVW_FUSION)
  s.fusedCount = 0;
  s.fusedOrigin = (uFunctionalFromWorld * vec4(ray.origin, 1.0)).xyz;
  s.fusedDir = (uFunctionalFromWorld * vec4(ray.dir, 0.0)).xyz;
#endif
}

#if defined(MVW_FUSION) && !defined(MVW_FUSION_MEAN)
// The (cued) fraction the functional volume adds at the ray's sample t to the maximum, -1
// where none (outside its box, or at or under the threshold).
float fusedPhi(RayState s, float t) {
  bool inside;
  float u = overlayFractionAt(s.fusedOrigin + t * s.fusedDir, inside);
  if (!(inside && u > uOverlayThreshold)) return -1.0;  // a NaN too
  float phi = clamp(u, 0.0, 1.0);
#if defined(MVW_DEPTH_CUE)
  phi *= max(s.cue0 - s.cue1 * t, 0.0);  // eq. (3): beta(z') phi(z), before the maximum
#endif
  return phi;
}
#endif

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
#if defined(MVW_MIP) && !defined(MVW_DEPTH_CUE) && !defined(MVW_NEAREST)
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
}
#endif

// Empty-space skipping by the block min/max grid (one-voxel apron, so no trilinear sample in a
// block leaves its range): a block whose maximum cannot beat the ray's maximum so far (MIP; with
// the depth cue, that maximum's emission under the cue at this sample, which only falls along
// the ray), or whose minimum cannot go below its minimum (MinIP), holds no sample that changes
// the result; ties keep the first sample, so none is lost. Average reads every sample.
// anatomySettled: no sample of the anatomy in the block (its range r) changes the projection.
#if defined(MVW_MIP) && defined(MVW_DEPTH_CUE)
bool anatomySettled(RayState s, float t, vec2 r) {
  return max(s.cue0 - s.cue1 * t, 0.0) * clamp(r.y * s.scale + s.offset, 0.0, 1.0) <= s.value;
}
#elif defined(MVW_MIP)
bool anatomySettled(RayState s, float t, vec2 r) { return r.y <= s.value || r.y < s.bound; }
#elif defined(MVW_MINIP)
bool anatomySettled(RayState s, float t, vec2 r) { return r.x >= s.value; }
#else
bool anatomySettled(RayState s, float t, vec2 r) { return false; }
#endif
#if defined(MVW_FUSION) && !defined(MVW_FUSION_MEAN)
// A fused projection's maximum: no functional sample in the block (its range r, the fused
// grid's BA) changes it where even the block's maximum, as fusedPhi would take it at this
// sample (fraction and cue fall monotonically with the value and along the ray), is at or
// under the threshold or the maximum so far. The mean reads every sample, and so its
// projection (average, minip) skips nothing. The functional volume's part of the test, and the
// state and sample it was made at, are kept for what follows in the loop (the lean loop's
// hand-over, the full loop's hand-back).
bool gFunctionalSettled;
RayState gState;
float gT;
bool skipHook(RayState s, float t, vec3 tex) {
  gState = s;
  gT = t;
  vec4 r = texelFetch(uBlockRange, blockOf(tex), 0);
  float u = (r.w - uFunctionalRange.x) / (uFunctionalRange.y - uFunctionalRange.x);
  float phi = clamp(u, 0.0, 1.0);
#if defined(MVW_DEPTH_CUE)
  phi *= max(s.cue0 - s.cue1 * t, 0.0);
#endif
  gFunctionalSettled = u <= uOverlayThreshold || phi <= s.fused;
  return anatomySettled(s, t, r.xy) && gFunctionalSettled;
}
#elif defined(MVW_FUSION)
bool skipHook(RayState s, float t, vec3 tex) { return false; }
#else
bool skipHook(RayState s, float t, vec3 tex) { return anatomySettled(s, t, blockRange(tex)); }
#endif

#if defined(MVW_FUSION)
// The functional volume at the ray's sample t (see the top of this file).
void fuseSample(inout RayState s, float t, Ray ray) {
#if defined(MVW_FUSION_MEAN)
  bool inside;
  float u = overlayFractionAt(s.fusedOrigin + t * s.fusedDir, inside);
  if (inside) {
    s.fused += u;
    s.fusedCount++;
  }
#else
  s.fused = max(s.fused, fusedPhi(s, t));  // -1 (none) leaves it as it is
#endif
}
#endif

// The anatomy's projection at a sample of `value`.
void anatomySample(inout RayState s, float t, float value) {
#if defined(MVW_MIP)
#if defined(MVW_DEPTH_CUE)
  value = (s.cue0 - s.cue1 * t) * clamp(value * s.scale + s.offset, 0.0, 1.0);  // eq. (3): beta(z') phi(z)
#endif
  // Strictly greater: of equally bright samples the first, nearest the viewer, wins.
  if (value > s.value) { s.value = value; s.depth = t; }
#elif defined(MVW_MINIP)
  if (value < s.value) { s.value = value; s.depth = t; }
#else
  s.value += value;
#endif
  s.count++;
}

bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
#if defined(MVW_FUSION)
  fuseSample(s, t, ray);
#endif
  anatomySample(s, t, value);
  return true;
}

#if defined(MVW_FUSION) && !defined(MVW_FUSION_MEAN)
// A fused maximum's rays start in the lean loop, which reads the anatomy alone: llvmpipe runs
// the full loop's second fetch on every sample, skipped or not. A sample in a block where the
// functional volume cannot change the projection (skipHook just said so) is the anatomy's
// alone; the first elsewhere is handed over, and the full loop reads both from there on.
#define RAY_LEAN_LOOP
float leanSampleValue(vec3 tex) { return sampleValue(tex); }
int leanSampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
  if (!gFunctionalSettled) return 2;
  anatomySample(s, t, value);
  return 0;
}
#if defined(MVW_MIP) || defined(MVW_MINIP)
// Past a hot spot, back to the lean loop at a sample that changes neither projection: the
// functional volume's settled in its block, and the anatomy's value is one its block test
// would have passed (average: every sample changes the sum, so no hand-back).
#define RAY_HAND_BACK
bool handBackHook(float value) {
  return gFunctionalSettled && anatomySettled(gState, gT, vec2(value));
}
#endif
#endif

void finishHook(inout RayState s, Ray ray, vec2 span) {
  if (s.count == 0) {
    fragColor = vec4(backgroundColour(uBackground), 1.0);
    fragDepth = -1.0;
    return;
  }
  float v = s.value;
#if defined(MVW_AVERAGE)
  v /= float(s.count);
#endif
  float grey = emission(v);
#if defined(MVW_MIP) && defined(MVW_DEPTH_CUE)
  // eq. (3): the background term beta0 Phi[0] competes in the maximum.
  grey = clamp(max(v, uCue.x * dot(uBackground, vec3(1.0 / 3.0))), 0.0, 1.0);
#endif
  vec3 colour = imageColour(grey);
#if defined(MVW_FUSION_MEAN)
  float mean = s.fusedCount > 0 ? s.fused / float(s.fusedCount) : 0.0;
  if (s.fusedCount > 0 && mean > uOverlayThreshold) colour = blendOverlay(colour, mean);
#elif defined(MVW_FUSION)
  if (s.fused >= 0.0) colour = blendOverlay(colour, s.fused);
#endif
  fragColor = vec4(colour, 1.0);
  fragDepth = s.depth;
}

#include "raycast/template.glsl"
