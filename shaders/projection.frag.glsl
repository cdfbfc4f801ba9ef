// Projections with window/level: MIP (maximum; ties keep the sample nearest the viewer),
// MinIP (minimum) and average intensity (X-ray-like). Chosen by MVW_MIP, MVW_MINIP or
// MVW_AVERAGE. No empty-space skipping: measured on llvmpipe, a per-sample block test for
// "this block cannot beat the current maximum" made MIP 3x slower (82 -> 256 ms/frame).
#include "raycast/common.glsl"

uniform vec2 uWindowLevel;  // window width, level (centre), in the volume's unit

struct RayState {
  float value;
  float depth;
  int count;
};

void setupHook(inout RayState s) {
#if defined(MVW_MINIP)
  s.value = 3.4e38;
#elif defined(MVW_MIP)
  s.value = -3.4e38;
#else
  s.value = 0.0;
#endif
  s.depth = -1.0;
  s.count = 0;
}

bool skipHook(RayState s, vec3 tex) { return false; }

bool sampleHook(inout RayState s, float t, vec3 tex, float value, Ray ray) {
#if defined(MVW_MIP)
  if (value > s.value) { s.value = value; s.depth = t; }
#elif defined(MVW_MINIP)
  if (value < s.value) { s.value = value; s.depth = t; }
#else
  s.value += value;
#endif
  s.count++;
  return true;
}

void finishHook(inout RayState s, Ray ray, vec2 span) {
  if (s.count == 0) {
    fragColor = vec4(uBackground, 1.0);
    fragDepth = -1.0;
    return;
  }
  float v = s.value;
#if defined(MVW_AVERAGE)
  v /= float(s.count);
#endif
  float grey = clamp((v - (uWindowLevel.y - 0.5 * uWindowLevel.x)) / uWindowLevel.x, 0.0, 1.0);
  fragColor = vec4(vec3(grey), 1.0);
  fragDepth = s.depth;
}

#include "raycast/template.glsl"
