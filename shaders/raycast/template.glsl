// The ray-caster template. A mode file includes raycast/common.glsl, declares RayState, defines
// the hooks and the loop macros it uses, then includes this file. The hooks:
//   void setupHook(inout RayState s, Ray ray)                 every mode; before the first sample
//   void prepassHook(inout RayState s, float t0, float tEnd)  with RAY_PREPASS; after setupHook,
//                          before the first loop (t0: sample 0's distance, tEnd: the box's exit)
//   bool skipHook(RayState s, float t, vec3 tex)  every mode; in every loop, first thing per
//                          sample: true, nothing in this block can change the result (the loop
//                          skips to the block's exit)
//   bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray)
//                          every mode; the full loop's sample: false ends the ray (early
//                          termination)
//   void finishHook(inout RayState s, Ray ray, vec2 span)  every mode; writes fragColor and
//                          fragDepth
//   bool entryHook(inout RayState s, Ray ray, vec2 span)  with RAY_ENTRY_HOOK; once per ray that
//                          meets the box, before the first loop: false ends the ray at its
//                          entry (composite's opaque cut face, MVW_CUT_FACE)
//   float leanSampleValue(vec3 tex)  with RAY_LEAN_LOOP; the value the lean loop reads (it may
//                          read less than sampleValue: one channel, not the packed texel)
//   int leanSampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray)
//                          with RAY_LEAN_LOOP; the lean loop's sample, sampleHook without its
//                          costly part: kRayGoOn, kRayEnd (end the ray), kRayHandOver (hand
//                          this sample and the rest of the ray over: to the middle loop, else
//                          the full loop); the constants: raycast/common.glsl
//   int middleSampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray)
//                          with RAY_MIDDLE_LOOP; the middle loop's sample: kRayGoOn, kRayEnd,
//                          kRayHandOver (this sample and the rest of the ray to the full loop)
//   bool handBackHook(float value)  with RAY_HAND_BACK or RAY_MIDDLE_LOOP; true: a sample of
//                          this value leaves the ray state as it is (sampleHook would do
//                          nothing), so the loop passes it and hands the ray back to the lean loop
// The loop macros (RAY_*, defined by the mode file; MVW_* are the variants C++ defines):
//   RAY_LEAN_LOOP    the ray starts in the lean loop and runs in rounds (below)
//   RAY_MIDDLE_LOOP  a middle loop between the lean and the full loop; needs RAY_LEAN_LOOP
//   RAY_HAND_BACK    the full loop hands the ray back to the lean loop; needs RAY_LEAN_LOOP
//   RAY_PREPASS      prepassHook runs before the first loop
//   RAY_ENTRY_HOOK   entryHook runs before the first loop and may end the ray there
// Without RAY_LEAN_LOOP the full loop alone runs the whole ray. With it, in rounds ([...]:
// only with its macro):
//
//   setupHook -> [prepassHook] -> lean loop --H--> [middle loop] --H--> full loop
//                                   ^                   |                  |
//                                   |   handBackHook    |                  | handBackHook
//                                   +-------------------+------------------+ [RAY_HAND_BACK]
//   [entryHook] runs between prepassHook and the first loop; false: no loop runs.
//   (H: kRayHandOver.) Any loop ends the ray (-> finishHook) at kRayEnd or false from its
//   hook, the box's exit or uMaxSteps; a sample handed over is sampled again by the next loop,
//   one handed back is passed, so every round advances by a sample at least.
//
// RayState is declared by the mode. fragDepth is the ray distance (mm) of the sample the
// mode reports (first hit, maximum, ...), or -1 where the ray reports none.
#if !defined(MVW_RAYCAST_COMMON)
#error "include raycast/common.glsl before raycast/template.glsl"
#endif
#if defined(RAY_HAND_BACK) && !defined(RAY_LEAN_LOOP)
#error "RAY_HAND_BACK hands the ray back to the lean loop: define RAY_LEAN_LOOP (and leanSampleValue, leanSampleHook) too"
#endif
#if defined(RAY_MIDDLE_LOOP) && !defined(RAY_LEAN_LOOP)
#error "RAY_MIDDLE_LOOP runs between the lean loop and the full loop: define RAY_LEAN_LOOP (and leanSampleValue, leanSampleHook) too"
#endif
void main() {
  Ray ray = makeRay();
  setupRayConstants(ray);
  setupLight(ray.dir);
  vec2 span = intersectBox(ray);
  gRayEntry = span.x;
  RayState s;
  setupHook(s, ray);
  if (span.x < span.y) {
    // Without jitter, samples sit at the middle of each step (midpoint rule): a ray through a
    // slab of thickness L takes exactly L / step samples. Sample n lies at sampleDistance(t0, n),
    // computed afresh (not summed step by step): no rounding builds up along a long ray, and a
    // mode's pre-pass over every k-th sample reads the very samples the ray will.
    float t0 = span.x + (uJitter ? jitterOffset() : 0.5) * uStep;
#if defined(RAY_PREPASS)
    prepassHook(s, t0, span.y);
#endif
    int i = 0;
    float n = 0.0;  // whole numbers, exact in a float up to 2^24 samples
    bool rest = true;
#if defined(RAY_ENTRY_HOOK)
    rest = entryHook(s, ray, span);
#endif
    // Each loop spells out its first lines, the sample's distance, the box's end and the skip,
    // and the full loop is written out twice (in rounds, and alone): as one function returning
    // what to do, composite and MIP took 4-5 % longer.
#if defined(RAY_LEAN_LOOP)
    // Rounds of the lean loop up to a sample it hands over, (RAY_MIDDLE_LOOP) the middle loop,
    // then the full loop from the sample handed over on, until the full loop ends the ray or
    // (RAY_HAND_BACK) meets a sample that changes nothing and hands the ray back. A ray through
    // a thin bone thus crosses the transparent tissue behind it in the lean loop again, not in
    // the full one (which llvmpipe runs whole for every sample).
    while (rest) {
      bool handed = false;
      for (; i < uMaxSteps; ++i, n += 1.0) {
        float t = sampleDistance(t0, n);
        if (t > span.y) break;
        vec3 tex = textureAt(t);
        if (skipHook(s, t, tex)) {
          n += skipSteps(t, tex);
          continue;
        }
        int next = leanSampleHook(s, t, tex, leanSampleValue(tex), ray);
        if (next == kRayEnd) rest = false;
        if (next != kRayGoOn) {
          handed = true;
          break;
        }
      }
      if (!handed) break;
#if defined(RAY_MIDDLE_LOOP)
      // The middle loop, from the sample the lean loop handed over: it hands the ray back to
      // the lean loop at the next sample that changes nothing, passing it, and on to the full
      // loop at a sample middleSampleHook leaves to sampleHook (kRayHandOver), not passing it.
      bool toFull = false;
      for (; rest && i < uMaxSteps; ++i, n += 1.0) {
        float t = sampleDistance(t0, n);
        if (t > span.y) {
          rest = false;
          break;
        }
        vec3 tex = textureAt(t);
        if (skipHook(s, t, tex)) {
          n += skipSteps(t, tex);
          continue;
        }
        float value = sampleValue(tex);
        if (handBackHook(value)) {
          ++i;
          n += 1.0;
          break;
        }
        int next = middleSampleHook(s, t, tex, value, ray);
        if (next == kRayEnd) rest = false;
        if (next != kRayGoOn) {
          toFull = next == kRayHandOver;
          break;
        }
      }
      if (i >= uMaxSteps) rest = false;
      if (!toFull) continue;
#endif
      // The full loop, the same as the one below but for the hand-back.
      for (; rest && i < uMaxSteps; ++i, n += 1.0) {
        float t = sampleDistance(t0, n);
        if (t > span.y) {
          rest = false;
          break;
        }
        vec3 tex = textureAt(t);
        if (skipHook(s, t, tex)) {
          n += skipSteps(t, tex);
          continue;
        }
        float value = sampleValue(tex);
#if defined(RAY_HAND_BACK)
        if (handBackHook(value)) {
          ++i;
          n += 1.0;
          break;
        }
#endif
        if (!sampleHook(s, t, tex, value, ray)) {
          rest = false;
          break;
        }
      }
      if (i >= uMaxSteps) rest = false;
    }
#else
    // The full loop alone, the whole ray.
    for (; rest && i < uMaxSteps; ++i, n += 1.0) {
      float t = sampleDistance(t0, n);
      if (t > span.y) {
        rest = false;
        break;
      }
      vec3 tex = textureAt(t);
      // Tested per sample: caching the test once per block entered left ring artefacts on
      // isosurfaces of ch2better (iso 60); the cause was not pinned down, so no caching.
      if (skipHook(s, t, tex)) {
        n += skipSteps(t, tex);
        continue;
      }
      float value = sampleValue(tex);
      if (!sampleHook(s, t, tex, value, ray)) {
        rest = false;
        break;
      }
    }
    if (i >= uMaxSteps) rest = false;
#endif
  }
  finishHook(s, ray, span);
}
