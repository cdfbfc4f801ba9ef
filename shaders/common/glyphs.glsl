// Volumetric normal glyphs (Seipel 2007): the shading normal of the anatomy is perturbed by
// spherical normal glyphs from a periodic normal map, weighted by the functional attribute
// beta at the sample, so bumps (or dimples) appear where the attribute is.
// Pasted before composite's or isosurface's own file where glyphs are on (the glyphs feature,
// RaycastFeatures.cpp).
#ifndef MVW_COMMON_GLYPHS
#define MVW_COMMON_GLYPHS
#include "raycast/common.glsl"

// The normal map in its compact form (modules/render GlyphMap): the map cut into cells, each
// naming the one glyph that reaches into it (0: none), and the glyph centres. N_G and A are
// evaluated from the centre exactly: what the RGBA map's texels hold, between texels too.
uniform usampler3D uGlyphCells;   // R8UI, repeats: 1 + glyph index, 0 = no glyph
layout(std140) uniform GlyphCentres {
  vec4 uGlyphCentres[255];        // map voxel coordinates
};
// Map voxel coordinates from world mm: the map's scale and, for the blue-noise lattice, a fixed
// oblique rotation (GlyphMap.h: glyphMapRotation) so that no axial, coronal or sagittal cut
// runs along one of the lattice's layers.
uniform mat3 uGlyphFromWorld;
uniform float uGlyphMapSize;      // map voxels per period
uniform float uGlyphInvMapSize;   // 1 / uGlyphMapSize (the loop multiplies, never divides)
uniform float uGlyphRadius;       // map voxels
// The smallest apparent bump radius (fraction of the glyph radius), the one an attribute just
// above the window's low end gets (see glyphNormal).
uniform float uGlyphMinSize;
// Composite DVR: the least opacity per step of a sample a bump tilts (beyond the paper).
uniform float uGlyphAlpha;
// Method and shading are compile-time variants, like every feature switch in the ray loop:
// MVW_GLYPH_SIMPLE: simple blending, eq. (1) (default: size and convexity control, eqs. 2-3);
// the shading (GlyphShading, one of them at most): MVW_GLYPH_CONCAVE: dimples; MVW_GLYPH_BOTH:
// dimples below the middle of the attribute's range, bumps above; MVW_GLYPH_KINDS: each
// glyph's kind (below); none: convex bumps. MVW_GLYPH_PAPER (the paper's placement): the
// paper's own size rule and shading, so its figures can be reproduced (otherwise: the
// extensions below, marked "beyond the paper").
#if (defined(MVW_GLYPH_CONCAVE) && (defined(MVW_GLYPH_BOTH) || defined(MVW_GLYPH_KINDS))) || (defined(MVW_GLYPH_BOTH) && defined(MVW_GLYPH_KINDS))
#error "one glyph shading at most: MVW_GLYPH_CONCAVE, MVW_GLYPH_BOTH or MVW_GLYPH_KINDS (GlyphShading)"
#endif

#if defined(MVW_GLYPH_KINDS)
// Glyph kinds (issue 40, beyond the paper: "more complexly shaped volumetric normal glyphs"):
// the attribute is 2 k + size for kind k (mvw::GlyphKind's order), read at the glyph's foot
// (the point of the surface's tangent plane under its centre), so a whole glyph takes one kind
// even where the labels beside it differ. Worked in world mm (the map is rotated and scaled).
uniform mat3 uWorldFromGlyph;  // the inverse of uGlyphFromWorld
uniform float uGlyphRadiusMm;
// The attribute at the anatomical voxel nearest `world`, not interpolated: a kind must not
// blend with its neighbour's (raycast/common.glsl).
float glyphAttributeNearest(vec3 world);
// Composite DVR, one layer (issue 52 prototype, RenderSettings::glyphLayerMm; 0: off): the
// glyph's centre must lie at most gGlyphMaxDepth mm beyond the sample along the frame's
// opposite (the ray), set per sample by composite.frag.glsl; 1e30: no limit.
uniform float uGlyphLayerMm;
float gGlyphMaxDepth = 1e30;

// A kind's shape: the normal at tv on the glyph's disc (|tv| = r < 1, in the plane normal to
// frame), or nO where the shape leaves the surface flat.
vec3 glyphKindShape(int k, vec3 tv, float r, vec3 frame, vec3 nO) {
  vec3 radial = tv / max(r, 1e-4);
  if (k == 0) return sqrt(max(1.0 - r * r, 0.0)) * frame + tv;  // bumps: a hemisphere
  if (k == 1) return sqrt(max(1.0 - r * r, 0.0)) * frame - tv;  // dimples: a bowl
  if (k == 2) {
    // Rings: a torus of tube radius 0.4 around r = 0.6, the centre left flat.
    float q = (r - 0.6) * 2.5;
    if (abs(q) >= 1.0) return nO;
    return sqrt(1.0 - q * q) * frame + q * radial;
  }
  if (k == 4) {
    // Cones: a peak with concave flanks, steep at the tip (75 degrees) and easing to 20 at
    // the foot, so that even under a headlight it shades from a dark tip to a light rim.
    float tilt = mix(1.309, 0.3491, r);
    return cos(tilt) * frame + sin(tilt) * radial;
  }
  // Ridges and crosses: bars (half-cylinders) across the disc, one along the patient's S axis
  // (L where the surface faces within 60 degrees of S), crosses with a second at right angles.
  vec3 e = vec3(0.0, 0.0, 1.0) - frame.z * frame;
  if (dot(e, e) < 0.25) e = vec3(1.0, 0.0, 0.0) - frame.x * frame;
  e = normalize(e);
  vec3 b = cross(frame, e);
  float across = dot(tv, b) * 2.5;  // bar half-width 0.4 of the disc's radius
  if (k == 5) {
    float along = dot(tv, e) * 2.5;
    if (abs(along) < abs(across)) {
      across = along;
      b = e;
    }
  }
  if (abs(across) >= 1.0) return nO;
  return sqrt(1.0 - across * across) * frame + across * b;
}

// d: from the glyph's centre to the sample (map voxels); p: the sample (map voxels).
vec3 glyphKindNormal(vec3 p, vec3 d, vec3 nO, vec3 frame) {
  vec3 dw = uWorldFromGlyph * d;
  float h = dot(dw, frame);
  vec3 tw = dw - h * frame;  // along the surface, from the glyph's foot
  if (h > gGlyphMaxDepth) return nO;  // the centre lies beyond the layer
  float a = glyphAttributeNearest(uWorldFromGlyph * p - tw);
  if (a <= 0.0) return nO;
  float kind = floor(a * 0.5);
  float size = mix(uGlyphMinSize, 1.0, clamp(a - 2.0 * kind, 0.0, 1.0));
  float r2 = uGlyphRadiusMm * uGlyphRadiusMm;
  // The apparent radius: the size's, at most the chord the surface cuts (as for bumps below).
  // A glyph the surface only grazes (its chord under 0.6 of the apparent radius) is left out:
  // too small for its shape to be read, it would only be a speck of some kind.
  float rho2 = min(size * size * r2, r2 - h * h);
  float t2 = dot(tw, tw);
  if (rho2 < 0.36 * size * size * r2 || t2 >= rho2) return nO;
  vec3 tv = tw * inversesqrt(rho2);  // |tv| < 1: the position on the glyph's disc
  return glyphKindShape(int(kind), tv, sqrt(t2 / rho2), frame, nO);
}

// Glyphs on the visible surface (issue 52; GlyphStyle::onSurface): instead of the 3D
// lattice that the surface cuts at random depths, the glyph centres form a hexagonal lattice on
// the image (uGlyphScreenRadiusPx > 0: a glyph's radius in pixels, the centres
// uGlyphScreenSpacingPx apart: 2 / kBlueNoiseDiameterFraction radii), and each glyph's shape is laid out on the disc
// facing the viewer, so a kind's outline is the same whole disc on a gyral crown, a flank or a
// sphere. Isosurface: each pixel marches its glyph centre's own ray to the first hit
// (gGlyphSurfaceValue, the isovalue), reads the kind there, and draws the glyph only where it
// lies whole on the surface around that hit (glyphWholeScale: at its size, or shrunk to 0.75 or
// 0.5 of it) and only where the pixel's own hit lies within 1.5 glyph radii in depth of the
// centre's, so a glyph is drawn whole or not at all: at a fold's edge, on a sulcal wall or a
// grazing flank it is left out rather than cut into a fragment that reads as another kind
// (issue 52: 83 % -> 97 % on ch2better at 1024 px). Glyphs of more than
// kWholeGlyphMaxRadiusMm (wider than a gyrus) keep the per-pixel drawing instead: a pixel whose
// hit lies more than two glyph radii in depth from where its centre's ray meets the surface is
// left flat, so a glyph stops at a fold's edge. The shape's tilts are taken relative to
// the surface's own normal (its flat parts are the surface), as on the sphere. Composite: the
// kind is the attribute on the centre's ray at the depth of the pixel's own sample (its foot),
// so a glyph is whole across its region's edge, and the tilts are relative to the viewer (the
// frame of glyphNormalMapped), over the surface's own normal elsewhere.
uniform float uGlyphScreenRadiusPx;  // 0: the 3D lattice
uniform float uGlyphScreenSpacingPx;  // between neighbouring centres
uniform vec3 uGlyphScreenRight;      // world unit vectors of the image's x and y
uniform vec3 uGlyphScreenUp;
float gGlyphSurfaceValue = -1e30;  // set by isosurface.frag.glsl: its isovalue

// The anatomy's value at `world` as the isosurface sees it: what a crop cuts away from the
// volume is air, so that a crop's cut face is a surface like any other (issue 52: the lesions
// on an opaque cut); beyond the volume's edge, the edge's value (the texture's clamp).
float glyphSurfaceSample(vec3 world) {
  vec3 tex = toTexture(world);
  vec3 inVolume = clamp(tex, 0.0, 1.0);
  if (any(lessThan(inVolume, uBoxMin)) || any(greaterThan(inVolume, uBoxMax)) ||
      any(lessThan(world, uWorldBoxMin)) || any(greaterThan(world, uWorldBoxMax)))
    return -1e30;
  return sampleValue(tex);
}

// Isosurface: the first hit of a glyph centre's own ray (ray distance, mm; -1: none), marched
// as the isosurface's ray is (its steps, its empty-space skip, its bisection) but through the
// centre's pixel, so that every pixel of a glyph finds the same hit and takes the same
// decisions. Leaves the ray constants set for the centre's ray (the caller sets them back).
float glyphCentreHit(Ray c) {
  setupRayConstants(c);
  vec2 span = intersectBox(c);
  float t0 = span.x + 0.5 * uStep;
  float n = 0.0;
  for (int i = 0; span.x < span.y && i < uMaxSteps; ++i, n += 1.0) {
    float t = sampleDistance(t0, n);
    if (t > span.y) break;
    vec3 tex = textureAt(t);
    if (blockRange(tex).y < gGlyphSurfaceValue) {
      n += skipSteps(t, tex);
      continue;
    }
    if (sampleValue(tex) >= gGlyphSurfaceValue)
      return isoCrossing(c, max(t - uStep, span.x), t, gGlyphSurfaceValue);
  }
  return -1.0;
}

// Isosurface: the size (a fraction of `size`) at which the glyph on the centre's hit lies
// whole on the surface, 0 where it does not at half its size: the surface under six points of
// its rim (0.8 of its radius) crosses within 1.5 glyph radii in depth of the centre's hit, at
// its full size, else at 0.75, else at 0.5 of it. A glyph is drawn whole or not at all: a
// glyph a fold cuts is no fragment that reads as a bar (issue 52).
const float kWholeGlyphMaxRadiusMm = 5.0;
float glyphWholeScale(vec3 centreHit, vec3 frame, float size) {
  float tol = 1.5 * uGlyphRadiusMm;
  for (int s = 0; s < 3; ++s) {
    float scale = 1.0 - 0.25 * float(s);
    float rimMm = 0.8 * scale * size * uGlyphRadiusMm;
    bool fits = true;
    for (int k = 0; k < 6; ++k) {
      float angle = float(k) * 1.0471976;
      vec3 rim = centreHit + rimMm * (cos(angle) * uGlyphScreenRight + sin(angle) * uGlyphScreenUp);
      if (glyphSurfaceSample(rim + tol * frame) >= gGlyphSurfaceValue ||
          glyphSurfaceSample(rim - tol * frame) < gGlyphSurfaceValue)
        fits = false;
    }
    if (fits) return scale;
  }
  return 0.0;
}

// The attribute at `p`, or 1 mm under it (along -frame, away from the viewer) where there is
// none at `p`: a glyph's kind read on its centre's ray.
float glyphAttributeAtOrUnder(vec3 p, vec3 frame) {
  float a = glyphAttributeNearest(p);
  return a > 0.0 ? a : glyphAttributeNearest(p - frame);
}

vec3 glyphScreenNormal(vec3 world, vec3 nO) {
  vec3 frame = cross(uGlyphScreenRight, uGlyphScreenUp);  // towards the viewer
  float R = uGlyphScreenRadiusPx;
  float S = uGlyphScreenSpacingPx;
  float H = 0.8660254 * S;
  vec2 q = gl_FragCoord.xy - 0.5 * uViewport;  // a centre at the image's middle (a legend icon's)
  vec2 best = vec2(0.0);
  vec2 centre = vec2(0.0);
  float bestD2 = 1e30;
  float row0 = floor(q.y / H);
  for (int i = 0; i < 2; ++i) {
    float row = row0 + float(i);
    float offset = mod(row, 2.0) * 0.5 * S;
    vec2 c = vec2(floor((q.x - offset) / S + 0.5) * S + offset, row * H);
    vec2 dq = q - c;
    float d2 = dot(dq, dq);
    if (d2 < bestD2) bestD2 = d2, best = dq, centre = c;
  }
  if (bestD2 >= R * R) return nO;
  bool isosurface = gGlyphSurfaceValue > -1e29;
  // Whole glyphs up to kWholeGlyphMaxRadiusMm: a glyph wider than a gyrus (about 10 mm) rarely
  // lies whole anywhere on a cortex, and there the per-pixel drawing below reads better (issue
  // 52, ch2better at 512 px, 6.7 mm radii: the right hemisphere's isosurface 76.5 / 70.0 % drawn
  // per pixel, 29.7 / 58.3 % whole; at 1024 and 884 px, 3.4-3.9 mm, whole glyphs read 96-98 %).
  bool whole = isosurface && uGlyphRadiusMm <= kWholeGlyphMaxRadiusMm;
  // The centre's ray at the sample's depth.
  vec3 foot = world - (best.x * uGlyphScreenRight + best.y * uGlyphScreenUp) * (uGlyphRadiusMm / R);
  vec3 centreHit = vec3(0.0);
  float a = 0.0;
  if (whole) {
    // First a cheap test, so that only the glyphs over the attribute march their centre's ray
    // (an isosurface frame with kinds took 1.9x its time without glyphs, not 1.1x, where every
    // glyph marched): the attribute somewhere on the centre's ray within the depths its hit
    // can lie at for this pixel to be drawn (1.5 radii either side of the pixel's depth, and
    // the read 1 mm deeper), at the voxels' spacing.
    float reach = 1.5 * uGlyphRadiusMm;
    int count = min(int(ceil((2.0 * reach + 1.0) / uVolume.referenceStep)), 64);
    bool near = false;
    for (int j = 0; j <= count && !near; ++j)
      near = glyphAttributeNearest(foot + (reach - float(j) * uVolume.referenceStep) * frame) > 0.0;
    if (!near) return nO;
    // Everything from the centre's own hit, the same for every pixel of the glyph: the kind,
    // and whether (and at which size) the glyph lies whole on the surface.
    Ray c = makeRayAt(centre + 0.5 * uViewport);
    float tc = glyphCentreHit(c);
    setupRayConstants(makeRay());
    if (tc < 0.0) return nO;
    centreHit = c.origin + tc * c.dir;
    // The pixel sees the glyph's surface, not one in front of or behind it.
    if (abs(dot(world - centreHit, frame)) > 1.5 * uGlyphRadiusMm) return nO;
    a = glyphAttributeAtOrUnder(centreHit, frame);
  } else {
    a = glyphAttributeAtOrUnder(foot, frame);
    if (isosurface && a > 0.0) {
      // The centre's ray meets the surface within two glyph radii of the sample's depth, so a
      // glyph stops at a fold's edge instead of running down into the sulcus.
      float before = glyphSurfaceSample(foot + 2.0 * uGlyphRadiusMm * frame);
      float beyond = glyphSurfaceSample(foot - 2.0 * uGlyphRadiusMm * frame);
      if (before >= gGlyphSurfaceValue || beyond < gGlyphSurfaceValue) return nO;
    }
  }
  if (a <= 0.0) return nO;
  float kind = floor(a * 0.5);
  float size = mix(uGlyphMinSize, 1.0, clamp(a - 2.0 * kind, 0.0, 1.0));
  if (whole) {
    size *= glyphWholeScale(centreHit, frame, size);
    if (size <= 0.0) return nO;
  }
  float r = sqrt(bestD2) / (size * R);
  if (r >= 1.0) return nO;
  vec3 tv = (best.x * uGlyphScreenRight + best.y * uGlyphScreenUp) / (size * R);
  if (!isosurface) return glyphKindShape(int(kind), tv, r, frame, nO);
  // Isosurface: the shape turned from the viewer's frame onto the surface's normal (Rodrigues'
  // rotation taking frame to nO; a surface turned away from the viewer keeps the viewer's).
  vec3 g = glyphKindShape(int(kind), tv, r, frame, frame);
  vec3 v = cross(frame, nO);
  float c = dot(frame, nO);
  if (c <= 0.05) return g;
  return g * c + cross(v, g) + v * (dot(v, g) / (1.0 + c));
}
#endif

// nO: the unit outward surface normal of the anatomy at `world`; u: the functional attribute
// there, mapped to 0..1 (the gradient texture's alpha: see raycast/common.glsl).
// On a software rasteriser every line below runs for every sample (branches are masks, not
// jumps), so the tests are written without square roots or divisions where possible.
// frame: the normal the glyphs are measured against (eqs. 2-3); nO for a surface. Composite
// DVR passes the direction to the observer: its noisy soft-tissue gradients (the Cranium's
// brain) are no surface, and eq. (2)'s distance is the one "as seen from the observer", so
// every sample along a ray through a glyph tilts its normal the same way and the bump
// accumulates instead of averaging out over depth. Where mapping is denied: nO, bit for bit.
// p: the sample in map voxels, uGlyphFromWorld * world (composite DVR computes it only in the
// part of the ray that runs the glyph code: see composite.frag.glsl).
vec3 glyphNormalMapped(vec3 p, vec3 nO, vec3 frame, float u) {
#if defined(MVW_GLYPH_PAPER)
  frame = nO;
#endif
  // At or below the window's low end: the anatomy's own normal, bit for bit (for every method
  // and convexity: "both" would otherwise draw full dimples where there is no attribute).
#if defined(MVW_GLYPH_KINDS)
  // Glyphs on the surface: the kind is read at the glyph's foot, so a glyph is whole across
  // its region's edge (composite runs the glyph code only where the attribute is: u > 0).
  if (uGlyphScreenRadiusPx > 0.0) {
    if (gGlyphMaxDepth < 0.0) return nO;  // composite: beyond the one layer
    return glyphScreenNormal(uWorldFromGlyph * p, nO);
  }
#endif
  if (u <= 0.0) return nO;
#if defined(MVW_GLYPH_BOTH)
  float beta = 2.0 * u - 1.0;
#else
  float beta = u;
#endif
  if (beta == 0.0) return nO;
  uint cell = textureLod(uGlyphCells, p * uGlyphInvMapSize, 0.0).r;
  if (cell == 0u) return nO;   // outside every glyph
  vec3 d = p - uGlyphCentres[cell - 1u].xyz;
  d -= uGlyphMapSize * round(d * uGlyphInvMapSize);  // the nearest periodic copy of the centre
  float d2 = dot(d, d);
  float r2 = uGlyphRadius * uGlyphRadius;
  if (d2 >= r2) return nO;     // A >= 1: outside the glyph
#if defined(MVW_GLYPH_KINDS)
  return glyphKindNormal(p, d, nO, frame);
#endif
  vec3 nG = d * inversesqrt(max(d2, 1e-12));  // the glyph normal, away from its centre
#if defined(MVW_GLYPH_SIMPLE)
  return normalize(nO + beta * nG);  // eq. (1): N = N_O + beta N_G
#else
  float cosAlpha = dot(frame, nG);  // eq. (3): alpha = acos(N_O . N_G), N_O: the frame
  // Beyond the paper: where the surface cuts a glyph's far hemisphere (centre outside the
  // object, cos(alpha) < 0) the paper denies mapping, so half of the glyphs a surface meets
  // never show. Mirrored about the surface's tangent plane that hemisphere is a bump of the
  // same footprint and convexity, so every glyph the surface cuts shows: twice the coverage.
#if defined(MVW_GLYPH_PAPER)
  if (cosAlpha <= 0.0) return nO;
#else
  if (cosAlpha < 0.0) {
    nG -= 2.0 * cosAlpha * frame;
    cosAlpha = -cosAlpha;
  }
#endif
  // eq. (2): d = r sin(alpha) with r = A = |d| / radius, the fragment's distance from the bump's
  // centre along the surface; mapping is denied where d exceeds the apparent bump radius,
  // compared squared. Beyond the paper (where the threshold is beta itself, so an attribute
  // just above the window's low end makes a sub-pixel bump): the apparent radius runs from
  // uGlyphMinSize glyph radii at the low end to one glyph radius at the high end, linear in
  // |beta|, so the weakest finding is still a bump a reader sees and ordinal levels differ
  // in size.
  float cos2 = cosAlpha * cosAlpha;
  float t2 = d2 * (1.0 - cos2);  // (d * radius)^2: the squared distance along the surface
#if defined(MVW_GLYPH_PAPER)
  // The paper's rule: denied where d > |beta|, N_G itself as the bump's normal.
  if (t2 > beta * beta * r2) return nO;
#if defined(MVW_GLYPH_CONCAVE)
  return normalize(2.0 * cosAlpha * frame - nG);
#elif defined(MVW_GLYPH_BOTH)
  return beta < 0.0 ? normalize(2.0 * cosAlpha * frame - nG) : nG;
#else
  return nG;
#endif
#else
  float size = mix(uGlyphMinSize, 1.0, abs(beta));
  if (t2 > size * size * r2) return nO;
  // Beyond the paper: the bump's profile. The paper shades with N_G itself, so a glyph whose
  // centre lies deep under the surface tilts the normal only a little, and most bumps a
  // surface meets are faint specks. Here the bump is the hemisphere of the apparent radius
  // standing on the surface over the glyph's centre (rho: the apparent radius, at most the
  // chord the surface cuts from the glyph), which is N_G exactly where the surface passes
  // through the centre (the case of the paper's Figure 1, right), and every bump shows its
  // full light-to-shadow contrast.
  float invRho = inversesqrt(max(min(size * size * r2, r2 - cos2 * d2), 1e-6));
  vec3 tangential = (d - dot(d, frame) * frame) * invRho;
  vec3 up = sqrt(max(1.0 - t2 * invRho * invRho, 0.0)) * frame;
  // A dimple is the bump mirrored about the surface normal.
#if defined(MVW_GLYPH_CONCAVE)
  return up - tangential;
#elif defined(MVW_GLYPH_BOTH)
  return beta < 0.0 ? up - tangential : up + tangential;
#else
  return up + tangential;
#endif
#endif  // MVW_GLYPH_PAPER
#endif  // MVW_GLYPH_SIMPLE
}

vec3 glyphNormal(vec3 world, vec3 nO, float u) {
  return glyphNormalMapped(uGlyphFromWorld * world, nO, nO, u);
}

#endif
