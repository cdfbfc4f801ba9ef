// The functional volume (PET, SPECT, fMRI, labels) sampled at an anatomical world point
// through its own geometry and the registration: uFunctionalFromWorld maps anatomical world
// mm to functional texture coordinates, so no resampled copy is needed.
#ifndef MVW_COMMON_FUNCTIONAL
#define MVW_COMMON_FUNCTIONAL

uniform bool uHasFunctional;
uniform sampler3D uFunctional;        // R32F, physical values
uniform mat4 uFunctionalFromWorld;
uniform vec2 uFunctionalRange;        // values mapped to 0 .. 1 (colour map, glyph beta)

// The value at functional texture coordinates `tex`, and whether they lie inside its box.
float functionalValueAt(vec3 tex, out bool inside) {
  inside = all(greaterThanEqual(tex, vec3(0.0))) && all(lessThanEqual(tex, vec3(1.0)));
  return inside ? textureLod(uFunctional, tex, 0.0).r : 0.0;
}

// The value at `world`, and whether `world` lies inside the functional volume's box.
float functionalValue(vec3 world, out bool inside) {
  return functionalValueAt((uFunctionalFromWorld * vec4(world, 1.0)).xyz, inside);
}

// Nominal attributes (atlas labels): with uFunctionalClasses = K > 0 a label L > 0 maps to
// class (L mod K) + 1 of K, so neighbouring labels get distinct glyph sizes; 0 stays 0.
uniform int uFunctionalClasses;
// Labels chosen by the reader: uLabelGlyphCount > 0 looks each label up in uLabelGlyphs (1: a
// bump, just above 0: a dimple under the "both" shading, 0: none; labels past the table: none).
uniform sampler1D uLabelGlyphs;
uniform int uLabelGlyphCount;
// Glyph kinds for the classes (issue 40; the MVW_GLYPH_KINDS shading): class c of kind k is
// written as 2 k + its size; past the list's end the last kind. 0 kinds: sizes only.
uniform int uClassKinds[16];
uniform int uClassKindCount;

// 0 .. 1 over uFunctionalRange, or by class (0 outside the functional volume).
float functionalFraction(vec3 world) {
  bool inside;
  float v = functionalValue(world, inside);
  if (!inside) return 0.0;
  if (uLabelGlyphCount > 0) {
    int label = int(round(v));
    return label <= 0 || label >= uLabelGlyphCount ? 0.0 : texelFetch(uLabelGlyphs, label, 0).r;
  }
  if (uFunctionalClasses > 0) {
    int label = int(round(v));
    if (label <= 0) return 0.0;
    int c = label % uFunctionalClasses;
    float size = float(c + 1) / float(uFunctionalClasses);
    if (uClassKindCount > 0) return 2.0 * float(uClassKinds[min(c, uClassKindCount - 1)]) + size;
    return size;
  }
  float u = clamp((v - uFunctionalRange.x) / (uFunctionalRange.y - uFunctionalRange.x), 0.0, 1.0);
  // An ordinal attribute in classes (issue 40): the window cut into uClassKindCount equal
  // ranges, range c of kind uClassKinds[c], the size still u.
  if (uClassKindCount > 0 && u > 0.0)
    return 2.0 * float(uClassKinds[min(int(u * float(uClassKindCount)), uClassKindCount - 1)]) + u;
  return u;
}

// Colour fusion: the functional colour map blended over an anatomy colour where the attribute
// exceeds the threshold (MPR overlay, and DVR / isosurface fusion; the fused projections blend
// the functional projection of a whole ray, projection.frag.glsl).
uniform sampler1D uColormap;
uniform float uOverlayOpacity;
uniform float uOverlayThreshold;  // 0..1 of the functional range

// The value at functional texture coordinates `tex` as a fraction of uFunctionalRange (not
// clamped: the threshold and the mean see it as it is), and whether `tex` lies inside the
// functional volume's box.
float overlayFractionAt(vec3 tex, out bool inside) {
  float v = functionalValueAt(tex, inside);
  return (v - uFunctionalRange.x) / (uFunctionalRange.y - uFunctionalRange.x);
}

// The colour map at the fraction u (clamped to 0..1) blended over `anatomy` with the overlay's
// opacity.
vec3 blendOverlay(vec3 anatomy, float u) {
  return mix(anatomy, textureLod(uColormap, clamp(u, 0.0, 1.0), 0.0).rgb, uOverlayOpacity);
}

vec3 fuseColour(vec3 anatomy, vec3 world) {
  bool inside;
  float u = overlayFractionAt((uFunctionalFromWorld * vec4(world, 1.0)).xyz, inside);
  if (!inside || u <= uOverlayThreshold) return anatomy;
  return blendOverlay(anatomy, u);
}

#endif
