#include "GlyphTextures.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "TextureUpload.h"
#include "mvw/core/Error.h"

namespace mvw::render::detail {

void GlyphTextures::uploadMap(const GlyphMapSettings& g) {
  if (cells_.id() && g.size == settings_.size && g.count == settings_.count &&
      g.diameter == settings_.diameter && g.seed == settings_.seed &&
      g.placement == settings_.placement)
    return;
  const GlyphMap map = makeGlyphMap(g, /*texels=*/false);
  const int n = map.size / map.cellSize;
  cells_ = makeTexture();
  glBindTexture(GL_TEXTURE_3D, cells_.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R8UI, n, n, n, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
               map.cells.data());
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_REPEAT);  // the map is periodic
  setSampling(cells_.id(), GL_TEXTURE_3D, false);
  std::vector<glm::vec4> centres(255, glm::vec4(0.0f));  // std140: one vec4 per centre
  for (std::size_t i = 0; i < map.centres.size(); ++i)
    centres[i] = glm::vec4(glm::vec3(map.centres[i]), 0.0f);
  centres_ = makeBuffer();
  glBindBuffer(GL_UNIFORM_BUFFER, centres_.id());
  glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(centres.size() * sizeof(glm::vec4)), centres.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  checkGl("uploading the glyph map");
  settings_ = g;
  radius_ = map.radius;
}

// Beta sits in the gradient's alpha so that the ray loop reads it with the gradient instead of
// sampling a second volume per step, where that alpha is free (a float gradient texture);
// packed with 16-bit intensities or with the gradient taken on the fly, in an R16F volume of
// its own (VolumeTextures::betaTarget).
void GlyphTextures::updateBeta(VolumeTextures& volume, const FunctionalTextures& functional,
                               glm::vec2 window, int classes, const std::vector<LabelGlyph>& labels,
                               const std::vector<GlyphKind>& classKinds, bool kinds,
                               const ShaderProgram& p, GLuint vao) {
  // Chosen labels: a table over label numbers, 1 for a bump, just above 0 for a dimple (the
  // "both" shading: beta = 2u - 1), 0 for none; with kinds, 2 k + 1 for kind k at full size.
  std::vector<float> table;
  for (const LabelGlyph& l : labels)
    if (l.label > 0) table.resize(std::max<std::size_t>(table.size(), std::size_t(l.label) + 1));
  for (const LabelGlyph& l : labels)
    if (l.label > 0)
      table[std::size_t(l.label)] = kinds ? 2.0f * float(static_cast<int>(l.kind)) + 1.0f
                                    : l.kind == GlyphKind::Dimples ? 1e-3f
                                                                   : 1.0f;
  std::vector<int> kindCodes;
  for (GlyphKind k : classKinds) kindCodes.push_back(static_cast<int>(k));
  if (kindCodes.size() > 16) kindCodes.resize(16);  // uClassKinds[16]; the last one repeats
  const BetaKey key{functional.generation(), window.x, window.y, classes, table, kindCodes};
  if (betaKey_ == key) return;
  // First: made on first use, the target binds itself to the active unit, which must not
  // replace the functional volume bound below (it did, and glyphs had no attribute wherever
  // it lives in a volume of its own).
  const GLuint target = volume.betaTarget();
  p.use();
  functional.setUniforms(p, window, classes);
  if (!table.empty()) {
    labelTable_ = makeTexture();
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_1D, labelTable_.id());
    glTexImage1D(GL_TEXTURE_1D, 0, GL_R32F, GLsizei(table.size()), 0, GL_RED, GL_FLOAT,
                 table.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glUniform1i(p.uniform("uLabelGlyphs"), 1);  // never unit 0, the 3D functional volume's
  glUniform1i(p.uniform("uLabelGlyphCount"), GLint(table.size()));
  glUniform1i(p.uniform("uClassKindCount"), GLint(kindCodes.size()));
  if (!kindCodes.empty())
    glUniform1iv(p.uniform("uClassKinds"), GLsizei(kindCodes.size()), kindCodes.data());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, functional.texture());
  glUniform1i(p.uniform("uFunctional"), 0);
  Framebuffer fbo = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  const GLenum buffer = GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, &buffer);
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, 0, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw Error("the GL cannot render into the glyph attribute volume for glyph shading");
  }
  const glm::ivec3 dims = volume.dims();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  // Only the attribute's channel: the gradient texture keeps its gradient in RGB.
  const int channel = volume.betaChannel();
  glColorMask(channel == 0, channel == 1, channel == 2, channel == 3);
  glBindVertexArray(vao);
  // Layer by layer of the texture; a folded volume's runs of slices lie side by side along x
  // (VolumeTextures::foldRuns), each drawn in its own columns with its voxels' positions (the
  // last run's spare layers repeat the last slice, as its upload does).
  const int runs = volume.foldRuns();
  for (int layer = 0; layer < volume.textureDims().z; ++layer) {
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, 0, layer);
    for (int run = 0; run < runs; ++run) {
      const int column = run * dims.x;
      const glm::mat4 runWorldFromIndex(
          volume.worldFromIndex() * glm::translate(glm::dmat4(1.0), glm::dvec3(-column, 0.0, 0.0)));
      glUniformMatrix4fv(p.uniform("uWorldFromIndex"), 1, GL_FALSE,
                         glm::value_ptr(runWorldFromIndex));
      glViewport(column, 0, dims.x, dims.y);
      glUniform1f(p.uniform("uSlice"),
                  float(std::min(run * volume.foldSlices() + layer, dims.z - 1)));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("resampling the functional volume for glyph shading");
  betaKey_ = key;
}

void GlyphTextures::setUniforms(const ShaderProgram& p, double diameterMm, double minSize,
                                double dvrOpacityPerMm, double stepMm) const {
  const GLuint block = glGetUniformBlockIndex(p.id(), "GlyphCentres");
  if (block != GL_INVALID_INDEX) {
    glUniformBlockBinding(p.id(), block, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, centres_.id());
  }
  const glm::mat3 glyphFromWorld = this->glyphFromWorld(diameterMm);
  glUniformMatrix3fv(p.uniform("uGlyphFromWorld"), 1, GL_FALSE, glm::value_ptr(glyphFromWorld));
  glUniform1f(p.uniform("uGlyphMapSize"), float(settings_.size));
  glUniform1f(p.uniform("uGlyphInvMapSize"), float(1.0 / settings_.size));
  glUniform1f(p.uniform("uGlyphRadius"), float(radius_));
  glUniform1f(p.uniform("uGlyphMinSize"), float(std::clamp(minSize, 0.0, 1.0)));
  // Per mm to per step, as the transfer table's opacity: 1 - (1 - a)^(step / 1 mm).
  const double a = std::clamp(dvrOpacityPerMm, 0.0, 1.0);
  glUniform1f(p.uniform("uGlyphAlpha"), float(a >= 1.0 ? 1.0 : 1.0 - std::pow(1.0 - a, stepMm)));
}

void GlyphTextures::setKindsUniforms(const ShaderProgram& p, double diameterMm) const {
  const glm::mat3 worldFromGlyph(glm::inverse(glm::dmat3(glyphFromWorld(diameterMm))));
  glUniformMatrix3fv(p.uniform("uWorldFromGlyph"), 1, GL_FALSE, glm::value_ptr(worldFromGlyph));
  glUniform1f(p.uniform("uGlyphRadiusMm"), float(radius_ / (settings_.diameter / diameterMm)));
}

glm::mat3 GlyphTextures::glyphFromWorld(double diameterMm) const {
  const double voxelsPerMm = settings_.diameter / diameterMm;
  return glm::mat3(voxelsPerMm * glyphMapRotation(settings_.placement));
}

}  // namespace mvw::render::detail
