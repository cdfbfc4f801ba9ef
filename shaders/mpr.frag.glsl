// Multiplanar reformatting: the plane through the volume centre (moved by uPlaneOffset mm
// along the line of sight) facing the camera, with window/level. uSlab > 0 makes it a
// thick-slab MIP over that many mm. The functional volume, when present, is blended on top
// through a colour map where it exceeds the threshold; it is sampled at the same world
// point through its own textureFromWorld (which includes the registration), so no
// resampled copy is needed. Segment outlines, when a segmentation is set, go on top.
#include "raycast/common.glsl"
#include "common/functional.glsl"
#include "common/segments.glsl"
#include "common/colormap.glsl"

uniform vec3 uPlaneCentre;   // world mm
uniform float uSlab;         // mm, 0: a single plane
uniform vec2 uWindowLevel;   // window width, centre


bool inside(vec3 tex) { return all(greaterThanEqual(tex, uBoxMin)) && all(lessThanEqual(tex, uBoxMax)); }

void main() {
  Ray ray = makeRay();
  float t0 = dot(uPlaneCentre - ray.origin, ray.dir);
  vec3 world = ray.origin + t0 * ray.dir;
  vec3 pixelRight = dFdx(world), pixelUp = dFdy(world);  // uniform control flow here
  float value = -3.4e38;
  bool any = false;
  int n = uSlab > 0.0 ? max(1, int(ceil(uSlab / uStep))) : 1;
  for (int i = 0; i < n; ++i) {
    float dt = n > 1 ? (float(i) + 0.5) / float(n) * uSlab - 0.5 * uSlab : 0.0;
    vec3 tex = toTexture(world + dt * ray.dir);
    if (!inside(tex) || !insideWorldBox(world + dt * ray.dir)) continue;
    value = max(value, sampleValue(tex));
    any = true;
  }
  if (!any) {
    fragColor = vec4(backgroundColour(uBackground), 1.0);
    fragDepth = -1.0;
    return;
  }
  float grey = clamp((value - (uWindowLevel.y - 0.5 * uWindowLevel.x)) / uWindowLevel.x, 0.0, 1.0);
  vec3 rgb = imageColour(grey);
  if (uHasFunctional) rgb = fuseColour(rgb, world);
  rgb = outlineSegments(rgb, world, pixelRight, pixelUp);
  fragColor = vec4(rgb, 1.0);
  fragDepth = t0;
}
