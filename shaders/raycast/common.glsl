// Shared state of the ray caster: the volume as one struct uniform, rays in LPS world mm,
// box intersection in texture space, sampling. Distances t along a ray are world mm.
#ifndef MVW_RAYCAST_COMMON
#define MVW_RAYCAST_COMMON

// Outputs: colour, and the ray distance (mm) of the sample the mode reports (-1: none).
layout(location = 0) out vec4 fragColor;
layout(location = 1) out float fragDepth;

struct VolumeInfo {
  mat4 textureFromWorld;  // world mm -> texture coordinates (0..1 across the voxel box)
  vec3 dimensions;        // voxels
  float referenceStep;    // mm: opacity in transfer functions is per this step (min spacing)
  vec2 valueRange;        // min, max of the values (physical unit)
};

uniform VolumeInfo uVolume;
uniform sampler3D uIntensity;  // R16 (normalised) or R32F: texel * x + y of uValueMapping
uniform vec2 uValueMapping;    // is the physical value (HU, SUV, ...)
uniform sampler3D uGradient;   // RGBA16F: world-space gradient (unit/mm) in RGB; in A the functional
                               // attribute mapped to 0..1 on this grid (glyph beta), 0 without one.
                               // MVW_PACKED_GRADIENT (16-bit intensities): RGBA16, the gradient as
                               // texel * uGradientDecode.x + .y in RGB and the intensity's own texel
                               // in A, so that one fetch gives a composite sample both.
                               // MVW_GRADIENT_ON_THE_FLY: none
uniform sampler3D uAttribute;  // R16F: the glyph attribute where the gradient's A does not hold it
uniform vec2 uGradientDecode;
uniform usampler3D uBlocks;    // R8UI per 6^3 voxel block: 0 if the transfer function can show it,
                               // else the Chebyshev distance (blocks) to the nearest such block
uniform sampler3D uBlockRange; // RG32F per block: min and max value (one-voxel apron included)
uniform float uBlockVoxels;    // voxels per block side
uniform mat4 uWorldFromClip;
uniform vec2 uViewport;
uniform float uStep;           // mm
uniform int uMaxSteps;
uniform bool uJitter;
uniform uint uSeed;
uniform vec3 uBoxMin;          // crop box in texture coordinates
uniform vec3 uBoxMax;
uniform vec3 uWorldBoxMin;     // and in world mm (LPS), for an oblique volume's patient-axis crop;
uniform vec3 uWorldBoxMax;     // +-1e30 (no clip) where the texture box says it exactly
uniform vec3 uBackground;

float gRayEntry;  // where the current ray enters the box (mm), set by the template

// What a lean or middle loop's sample hook tells the loop (raycast/template.glsl).
const int kRayGoOn = 0;      // the next sample
const int kRayEnd = 1;       // the ray ends here
const int kRayHandOver = 2;  // this sample and the rest of the ray go to the next loop

struct Ray {
  vec3 origin;  // world mm
  vec3 dir;     // unit, world
};

// The ray through the pixel at fragCoord (gl_FragCoord's units): makeRay's, or (glyphs on the
// surface) a glyph centre's.
Ray makeRayAt(vec2 fragCoord) {
  vec2 ndc = fragCoord / uViewport * 2.0 - 1.0;
  vec4 nearPoint = uWorldFromClip * vec4(ndc, -1.0, 1.0);
  vec4 farPoint = uWorldFromClip * vec4(ndc, 1.0, 1.0);
  Ray r;
  r.origin = nearPoint.xyz / nearPoint.w;
  r.dir = normalize(farPoint.xyz / farPoint.w - r.origin);
  return r;
}

Ray makeRay() { return makeRayAt(gl_FragCoord.xy); }

vec3 toTexture(vec3 world) { return (uVolume.textureFromWorld * vec4(world, 1.0)).xyz; }

// Per ray (setupRayConstants, from the template): the ray and the block grid in texture
// space, so that the loop multiplies where it divided. llvmpipe runs every branch of the loop
// body on every iteration, the skip's arithmetic included (6 % of a composite frame).
vec3 gTexOrigin, gTexDir, gTexInvDir, gBlockScale, gBlockSize;
// skipSteps's per-ray part: a block face's distance along the ray is
// (its block coordinate) * gFaceScale + gFaceOffset (axes the ray runs parallel to: 1e30), and
// gFaceAhead picks the face the ray leaves through.
vec3 gFaceAhead, gFaceScale, gFaceOffset;
bvec3 gParallel;  // the ray is parallel to that axis's face pair (its direction 0.0 or -0.0)
ivec3 gBlockMax;
float gInvStep;
void setupRayConstants(Ray r) {
  gTexOrigin = toTexture(r.origin);
  gTexDir = (uVolume.textureFromWorld * vec4(r.dir, 0.0)).xyz;
  gParallel = lessThan(abs(gTexDir), vec3(1e-30));
  gTexInvDir = 1.0 / mix(gTexDir, vec3(1.0), gParallel);
  gBlockScale = uVolume.dimensions / uBlockVoxels;
  gBlockSize = uBlockVoxels / uVolume.dimensions;
  gBlockMax = ivec3(ceil(gBlockScale)) - 1;
  gInvStep = 1.0 / uStep;
  gFaceAhead = step(vec3(0.0), gTexDir);
  gFaceScale = mix(gBlockSize * gTexInvDir, vec3(0.0), gParallel);
  gFaceOffset = mix(-gTexOrigin * gTexInvDir, vec3(1e30), gParallel);
}

// Sample n of the ray: its distance (mm) from the first sample's t0, computed afresh rather
// than summed step by step, and its texture position (toTexture(ray.origin + t * ray.dir) in 3
// multiply-adds). The loops and a mode's pre-pass both call these, so they read the same
// samples.
float sampleDistance(float t0, float n) { return t0 + n * uStep; }
vec3 textureAt(float t) { return gTexOrigin + t * gTexDir; }

// Entry and exit distances (world mm) of the ray through the crop box; empty if x >= y.
// After setupRayConstants.
vec2 intersectBox(Ray r) {
  vec3 t0 = (uBoxMin - gTexOrigin) * gTexInvDir;
  vec3 t1 = (uBoxMax - gTexOrigin) * gTexInvDir;
  vec3 lo = min(t0, t1);
  vec3 hi = max(t0, t1);
  // A ray parallel to a face pair is inside that slab everywhere or nowhere.
  bvec3 inside = bvec3(uvec3(greaterThanEqual(gTexOrigin, uBoxMin)) &
                       uvec3(lessThanEqual(gTexOrigin, uBoxMax)));
  lo = mix(lo, mix(vec3(1e30), vec3(-1e30), inside), gParallel);
  hi = mix(hi, mix(vec3(-1e30), vec3(1e30), inside), gParallel);
  float tNear = max(max(lo.x, lo.y), max(lo.z, 0.0));
  float tFar = min(min(hi.x, hi.y), hi.z);
  vec3 invWorld = 1.0 / r.dir;
  vec3 w0 = (uWorldBoxMin - r.origin) * invWorld;
  vec3 w1 = (uWorldBoxMax - r.origin) * invWorld;
  vec3 wlo = min(w0, w1);
  vec3 whi = max(w0, w1);
  tNear = max(tNear, max(max(wlo.x, wlo.y), wlo.z));
  tFar = min(tFar, min(min(whi.x, whi.y), whi.z));
  return vec2(tNear, tFar);
}

bool insideWorldBox(vec3 world) {
  return all(greaterThanEqual(world, uWorldBoxMin)) && all(lessThanEqual(world, uWorldBoxMax));
}

// A hash of the pixel and the seed in [0, 1): seeded jitter against wood-grain artefacts,
// the same every run for the same seed.
float jitterOffset() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  uint h = p.x * 1973u + p.y * 9277u + uSeed * 26699u;
  h = (h ^ (h >> 16)) * 0x7feb352du;
  h = (h ^ (h >> 15)) * 0x846ca68bu;
  h ^= h >> 16;
  return float(h & 0xffffffu) / 16777216.0;
}

#if defined(MVW_FOLDED)
// A volume with more slices than the GL's largest 3D texture, folded (VolumeTextures): runs
// of uFold.x + 1 slices side by side along x, neighbouring runs sharing a slice. A sample
// reads the run that holds its slice position, its x clamped to that run's own columns as
// clamping to the edge does unfolded: the same voxels and weights as an unfolded texture.
uniform vec4 uFold;        // slices per run, runs - 1, the volume's width (voxels), 1 / texture width
uniform float uFoldDepth;  // 1 / the texture's depth (slices per run + 1)
vec3 storedTexture(vec3 tex) {
  float k = tex.z * uVolume.dimensions.z - 0.5;
  float run = clamp(floor(k / uFold.x), 0.0, uFold.y);
  float x = clamp(tex.x * uFold.z, 0.5, uFold.z - 0.5);
  return vec3((x + run * uFold.z) * uFold.w, tex.y, (k - run * uFold.x + 0.5) * uFoldDepth);
}
#else
vec3 storedTexture(vec3 tex) { return tex; }
#endif

// Level 0 explicitly: the volumes have no mipmaps, and implicit derivatives inside the ray
// loop cost a software rasteriser dearly.
#if defined(MVW_PACKED_VALUE)
// Composite with the packed gradient: the value from the gradient texture's A, and the texel
// kept for the gradient of the same sample (sampleGradientOfValue). Each texture fetch costs
// llvmpipe a loop iteration's share whether or not the sample needs it (it runs both sides of
// every branch), so one fetch instead of two cut a shaded frame by a fifth.
vec4 gPackedTexel;
float sampleValue(vec3 tex) {
  gPackedTexel = textureLod(uGradient, tex, 0.0);
  return gPackedTexel.a * uValueMapping.x + uValueMapping.y;
}
#else
float sampleValue(vec3 tex) {
  return textureLod(uIntensity, storedTexture(tex), 0.0).r * uValueMapping.x + uValueMapping.y;
}
#endif
#if defined(MVW_GLYPHS)
float sampleAttribute(vec3 tex) { return textureLod(uAttribute, storedTexture(tex), 0.0).r; }
#else
float sampleAttribute(vec3 tex) { return 0.0; }
#endif
#if defined(MVW_GLYPH_KINDS)
// The glyph attribute at the voxel nearest `world` (common/glyphs.glsl: a glyph's kind): the
// texture coordinate snapped to the texel's centre, where the linear filter returns the texel.
float glyphAttributeNearest(vec3 world) {
  vec3 tex = toTexture(world);
  tex = (floor(tex * uVolume.dimensions) + 0.5) / uVolume.dimensions;
#if defined(MVW_PACKED_GRADIENT) || defined(MVW_GRADIENT_ON_THE_FLY)
  return sampleAttribute(tex);
#else
  return textureLod(uGradient, tex, 0.0).a;
#endif
}
#endif
#if defined(MVW_GRADIENT_ON_THE_FLY)
// Central differences of the trilinear intensity one voxel either side along i, j, k, turned
// into a world gradient (unit/mm): no gradient volume in memory, six samples per call.
uniform vec3 uTexel;             // 1 / dimensions
uniform mat3 uGradientFromDelta; // direction * diag(1 / (2 spacing))
vec4 sampleGradient(vec3 tex) {
  vec3 delta = vec3(sampleValue(tex + vec3(uTexel.x, 0.0, 0.0)) -
                        sampleValue(tex - vec3(uTexel.x, 0.0, 0.0)),
                    sampleValue(tex + vec3(0.0, uTexel.y, 0.0)) -
                        sampleValue(tex - vec3(0.0, uTexel.y, 0.0)),
                    sampleValue(tex + vec3(0.0, 0.0, uTexel.z)) -
                        sampleValue(tex - vec3(0.0, 0.0, uTexel.z)));
  return vec4(uGradientFromDelta * delta, sampleAttribute(tex));
}
#elif defined(MVW_PACKED_GRADIENT)
vec4 decodeGradient(vec4 texel, vec3 tex) {
  return vec4(texel.xyz * uGradientDecode.x + uGradientDecode.y, sampleAttribute(tex));
}
vec4 sampleGradient(vec3 tex) { return decodeGradient(textureLod(uGradient, tex, 0.0), tex); }
#else
vec4 sampleGradient(vec3 tex) { return textureLod(uGradient, tex, 0.0); }
#endif
// The gradient where sampleValue last read (composite's samples): from the same fetch where
// the value comes packed with it.
#if defined(MVW_PACKED_VALUE)
vec4 sampleGradientOfValue(vec3 tex) { return decodeGradient(gPackedTexel, tex); }
#else
vec4 sampleGradientOfValue(vec3 tex) { return sampleGradient(tex); }
#endif

// Where `ray` crosses up to `value` between lo (below it) and hi (at or above): lo itself where
// lo already lies at or above (the ray enters the box inside the surface), else 8 halvings
// (1/256 of the span). The isosurface's hit, and (glyphs on the surface) a glyph centre's.
float isoCrossing(Ray ray, float lo, float hi, float value) {
  if (sampleValue(toTexture(ray.origin + lo * ray.dir)) >= value) return lo;
  for (int i = 0; i < 8; ++i) {
    float mid = 0.5 * (lo + hi);
    if (sampleValue(toTexture(ray.origin + mid * ray.dir)) >= value) hi = mid;
    else lo = mid;
  }
  return 0.5 * (lo + hi);
}

ivec3 blockOf(vec3 tex) { return clamp(ivec3(floor(tex * gBlockScale)), ivec3(0), gBlockMax); }
// Blocks around the current one that skipSteps steps over with it: a cube of side
// 2 gSkipReach + 1 blocks (set by a mode's skipHook; 0 is the block alone).
float gSkipReach = 0.0;
// Composite: whether the block can show anything, and if not, how many around it cannot either.
bool blockVisible(vec3 tex) {
  uint distance = texelFetch(uBlocks, blockOf(tex), 0).r;
  gSkipReach = float(distance) - 1.0;
  return distance == 0u;
}
vec2 blockRange(vec3 tex) { return texelFetch(uBlockRange, blockOf(tex), 0).rg; }

// How many more steps from the sample at t still lie in the block holding `tex`, or in the
// cube of gSkipReach blocks around it: the loop's next step after those lands in the following
// block (empty-space skipping).
// A ray parallel to a face pair never leaves through it. Not left to a division: a direction
// component the matrix product makes -0.0 (which axis, for which directions, follows the
// signs in the volume's storage order) picked the far face and divided to -inf, and the ray
// then crept through empty space one sample per iteration (2.7x the frame at some azimuths).
float skipSteps(float t, vec3 tex) {
  vec3 faces = vec3(blockOf(tex)) + gFaceAhead + gSkipReach * (2.0 * gFaceAhead - 1.0);
  vec3 tFaces = faces * gFaceScale + gFaceOffset;
  float tExit = min(min(tFaces.x, tFaces.y), tFaces.z);
  return max(0.0, floor((tExit - t) * gInvStep));
}

// Phong. By default a headlight (the light at the eye, along each ray); otherwise a
// directional light from uLightDir (world, unit, from the scene toward the light). Normals
// are made to face the viewer first, so surfaces are lit from either side. The light and
// halfway vectors depend on the ray alone: set once per ray (setupLight), not per sample.
uniform vec4 uLight;     // ambient, diffuse, specular, shininess
uniform bool uHeadlight;
uniform vec3 uLightDir;
vec3 gLight, gHalfway;
void setupLight(vec3 viewDir) {
  gLight = uHeadlight ? -viewDir : uLightDir;
  gHalfway = normalize(gLight - viewDir);
}
vec3 phong(vec3 color, vec3 n, vec3 viewDir) {
  if (dot(n, viewDir) > 0.0) n = -n;
  float diffuse = max(dot(n, gLight), 0.0);
  float specular = pow(max(dot(n, gHalfway), 0.0), uLight.w);
  return color * (uLight.x + uLight.y * diffuse) + vec3(uLight.z * specular);
}

#endif
