#pragma once
// Where the ray caster runs (internal to mvw_render): the back faces of the crop box, enlarged
// a little, drawn by box.vert.glsl. A pixel outside their projection has a ray that meets
// nothing, so it keeps the colour the target was cleared to, and the fragment shader (whose
// set-up alone cost about 9 ms of a 512^2 frame on llvmpipe) does not run for it.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/render/Camera.h"

namespace mvw::render::detail {

struct BoxProxy {
  glm::dmat4 clipFromTexture{1.0};
  glm::dvec3 min{0.0}, max{1.0};  // texture coordinates
  int faces = 0;                  // bit f: face f (axis f / 2, even f its low side) is drawn
  bool fullscreen = true;         // draw the whole viewport instead
};

// The proxy for the texture box [boxMin, boxMax] (boxMin <= boxMax on every axis; the caller
// orders a crop given high to low) seen by `camera`. Enlarged by a hundredth of
// the texture on each side, so that rounding in the rasteriser cannot leave out a pixel whose
// ray grazes the box; faces seen edge-on are drawn too (a pixel drawn twice gets the same
// colour twice). A perspective camera with a corner of the box on or behind its eye plane
// gets the whole viewport.
BoxProxy boxProxy(const Camera& camera, const glm::dmat4& textureFromWorld, glm::dvec3 boxMin,
                  glm::dvec3 boxMax);

}  // namespace mvw::render::detail
