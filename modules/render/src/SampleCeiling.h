#pragma once
// The sampling ceiling (issue 53; internal to mvw_render): how many trilinear samples of the
// volume's own intensity texture the GL delivers per second with a trivial shader
// (shaders/ceiling.frag.glsl), and how many samples a frame's rays would take without
// skipping, so that each mode's speed can be put as a fraction of that ceiling.
#include <memory>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "GlObjects.h"
#include "mvw/render/Camera.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render::detail {

class SampleCeiling {
 public:
  // Draws `size` pixels of `samples` fetches each of `intensity` (a 3D texture) into the
  // bound framebuffer and waits for the GL to finish: samples per second, the fastest of
  // `rounds` draws. The context must be current; the program is compiled on the first call.
  double samplesPerSecond(GLuint intensity, GLuint vertexArray, glm::ivec2 size, int samples,
                          int rounds);

 private:
  std::unique_ptr<ShaderProgram> program_;
};

// The samples the rays of a `size` image through `camera` take in the texture box
// boxMin..boxMax (textureFromWorld: world mm to the volume's texture coordinates) at `stepMm`
// without skipping: the sum over pixels of the length inside the box over the step.
double nominalSamples(const Camera& camera, glm::ivec2 size, const glm::dmat4& textureFromWorld,
                      glm::dvec3 boxMin, glm::dvec3 boxMax, double stepMm);

}  // namespace mvw::render::detail
