#include "SampleCeiling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <glad/gl.h>
#include <glm/common.hpp>

namespace mvw::render::detail {

double SampleCeiling::samplesPerSecond(GLuint intensity, GLuint vertexArray, glm::ivec2 size,
                                       int samples, int rounds) {
  if (!program_)
    program_ = std::make_unique<ShaderProgram>("fullscreen.vert.glsl", "ceiling.frag.glsl");
  program_->use();
  glUniform2f(program_->uniform("uViewport"), float(size.x), float(size.y));
  glUniform1i(program_->uniform("uSamples"), samples);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, intensity);
  glUniform1i(program_->uniform("uIntensity"), 0);
  glViewport(0, 0, size.x, size.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(vertexArray);
  double best = 1e300;
  for (int r = 0; r < rounds; ++r) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return double(size.x) * size.y * samples / best;
}

double nominalSamples(const Camera& camera, glm::ivec2 size, const glm::dmat4& textureFromWorld,
                      glm::dvec3 boxMin, glm::dvec3 boxMax, double stepMm) {
  // The rays as the shaders make them (raycast/common.glsl makeRay, intersectBox), in double.
  double total = 0.0;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const WorldRay ray =
          rayThrough(camera, (glm::dvec2(x, y) + 0.5) / glm::dvec2(size) * 2.0 - 1.0);
      const glm::dvec3 o = glm::dvec3(textureFromWorld * glm::dvec4(ray.origin, 1.0));
      const glm::dvec3 d = glm::dvec3(textureFromWorld * glm::dvec4(ray.direction, 0.0));
      double tNear = 0.0, tFar = 1e300;
      for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-30) {
          if (o[a] < boxMin[a] || o[a] > boxMax[a]) tFar = -1.0;
          continue;
        }
        const double t0 = (boxMin[a] - o[a]) / d[a], t1 = (boxMax[a] - o[a]) / d[a];
        tNear = std::max(tNear, std::min(t0, t1));
        tFar = std::min(tFar, std::max(t0, t1));
      }
      if (tFar > tNear) total += (tFar - tNear) / stepMm;
    }
  return total;
}

}  // namespace mvw::render::detail
