// The anatomy on a crop's cut face (MVW_CUT_FACE, issue 36 item 7): where a crop cuts an
// isosurface or a composite rendering, the opaque face shows the anatomy's grey value under
// the window, as an MPR on that plane shows it, the functional colour fused over it and the
// glyphs drawn on it, so a reader sees which tissue carries the attribute.
// Pasted before composite's or isosurface's own file (RaycastFeatures.cpp), after
// common/glyphs.glsl where glyphs are on.
#ifndef MVW_RAYCAST_CUT_FACE
#define MVW_RAYCAST_CUT_FACE
#include "raycast/common.glsl"
#include "common/functional.glsl"

uniform vec2 uWindowLevel;  // window width, centre (the anatomy's unit): the MPR's

// The glyphs' relief is shaded as on a surface of this grey (about the isosurface colour's
// brightness) and added to the face's own grey: a flat face is the MPR's grey exactly, whatever
// the light, and a glyph changes it by as much as it changes the plain isosurface's cut face.
const float kCutFaceRelief = 0.85;

// The cut face's colour at `hit` (world mm), whose anatomical value is `value` and glyph
// attribute `beta` (0: none); shaded: the glyph relief (composite without shading: none).
vec3 cutFaceColour(vec3 hit, vec3 viewDir, float value, float beta, bool shaded) {
  float grey =
      clamp((value - (uWindowLevel.y - 0.5 * uWindowLevel.x)) / uWindowLevel.x, 0.0, 1.0);
  vec3 colour = uHasFunctional ? fuseColour(vec3(grey), hit) : vec3(grey);
#if defined(MVW_GLYPHS)
  if (shaded) {
    vec3 facing = -viewDir;
    vec3 n = glyphNormal(hit, facing, beta);
    if (n != facing)
      colour += phong(vec3(kCutFaceRelief), n, viewDir) -
                phong(vec3(kCutFaceRelief), facing, viewDir);
  }
#endif
  return clamp(colour, 0.0, 1.0);
}

#endif
