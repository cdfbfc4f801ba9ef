// The ray-caster template. A mode file defines the hooks, then includes this file:
//   void setupHook(inout RayState s, Ray ray)              before the first sample
//   bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray)
//                                                          per sample; false ends the ray
//                                                          (early termination)
//   void finishHook(inout RayState s, Ray ray, vec2 span)  writes fragColor and fragDepth
//   bool skipHook(RayState s, float t, vec3 tex)           true: nothing in this block can
//                                                          change the result (skip to its exit)
//   int plainSampleHook(...)  (only where the mode defines MVW_SPLIT_LOOP) like sampleHook
//                             without its costly part: 0 go on, 1 end the ray, 2 hand this
//                             sample and the rest of the ray over to sampleHook
//   float plainSampleValue(vec3 tex)  (with MVW_SPLIT_LOOP) the value plainSampleHook gets
//   bool handBackHook(float value)  (where the mode also defines MVW_HAND_BACK or
//                             MVW_MIDDLE_LOOP) true: a sample of this value leaves the ray
//                             state as it is (sampleHook would do nothing), so the loop hands
//                             the rest of the ray back to the plain one
//   int middleSampleHook(...)  (only with MVW_MIDDLE_LOOP, which needs MVW_SPLIT_LOOP) run
//                             between the plain loop and the full one: 0 go on, 1 end the ray,
//                             2 hand this sample and the rest of the ray over to sampleHook
// RayState is declared by the mode. fragDepth is the ray distance (mm) of the sample the
// mode reports (first hit, maximum, ...), or -1 where the ray reports none.
#if defined(MVW_MIDDLE_LOOP) && !defined(MVW_SPLIT_LOOP)
#error "MVW_MIDDLE_LOOP runs inside MVW_SPLIT_LOOP's rounds: define both"
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
#if defined(MVW_PREPASS)
    prepassHook(s, t0, span.y);
#endif
    int i = 0;
    float n = 0.0;  // whole numbers, exact in a float up to 2^24 samples
    bool rest = true;
#if defined(MVW_SPLIT_LOOP)
    // Rounds of the plain loop up to a sample it hands over, (MVW_MIDDLE_LOOP) the middle
    // loop, then the full loop from the sample handed over on, until the full loop ends the ray
    // or (MVW_HAND_BACK) meets a sample that changes nothing and hands the ray back. A ray
    // through a thin bone thus crosses the transparent tissue behind it in the plain loop
    // again, not in the full one (which llvmpipe runs whole for every sample). Every round
    // advances by a sample at least.
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
        int next = plainSampleHook(s, t, tex, plainSampleValue(tex), ray);
        if (next == 1) rest = false;
        if (next != 0) {
          handed = true;
          break;
        }
      }
      if (!handed) break;
#endif
#if defined(MVW_MIDDLE_LOOP)
      // The middle loop, from the sample the plain loop handed over: it hands the ray back to
      // the plain loop at the next sample that changes nothing, passing it, and on to the full
      // loop at a sample middleSampleHook leaves to sampleHook (2), not passing it.
      // (Each loop spells out its first lines, the sample's distance, the box's end and the
      // skip: as one function returning what to do, composite and MIP took 4-5 % longer.)
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
        if (next == 1) rest = false;
        if (next != 0) {
          toFull = next == 2;
          break;
        }
      }
      if (i >= uMaxSteps) rest = false;
      if (!toFull) continue;
#endif
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
#if defined(MVW_HAND_BACK)
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
#if defined(MVW_SPLIT_LOOP)
    }
#endif
  }
  finishHook(s, ray, span);
}
