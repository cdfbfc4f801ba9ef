// The functional volume (PET, SPECT, fMRI, labels) sampled at an anatomical world point
// through its own geometry and the registration: uFunctionalFromWorld maps anatomical world
// mm to functional texture coordinates, so no resampled copy is needed.
#ifndef MVW_COMMON_FUNCTIONAL
#define MVW_COMMON_FUNCTIONAL

uniform bool uHasFunctional;
uniform sampler3D uFunctional;        // R32F, physical values
uniform mat4 uFunctionalFromWorld;
uniform vec2 uFunctionalRange;        // values mapped to 0 .. 1 (colour map, glyph beta)

// The value at `world`, and whether `world` lies inside the functional volume's box.
float functionalValue(vec3 world, out bool inside) {
  vec3 tex = (uFunctionalFromWorld * vec4(world, 1.0)).xyz;
  inside = all(greaterThanEqual(tex, vec3(0.0))) && all(lessThanEqual(tex, vec3(1.0)));
  return inside ? textureLod(uFunctional, tex, 0.0).r : 0.0;
}

// 0 .. 1 over uFunctionalRange (0 outside the functional volume).
float functionalFraction(vec3 world) {
  bool inside;
  float v = functionalValue(world, inside);
  return inside ? clamp((v - uFunctionalRange.x) / (uFunctionalRange.y - uFunctionalRange.x), 0.0, 1.0) : 0.0;
}

#endif
