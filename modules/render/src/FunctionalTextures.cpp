#include "FunctionalTextures.h"

#include <algorithm>
#include <vector>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "TextureUpload.h"
#include "mvw/render/TransferFunction.h"

namespace mvw::render::detail {

void FunctionalTextures::set(const Volume& functional, const glm::dmat4& anatomicalFromFunctional) {
  const std::vector<float> values = valuesOf(functional);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  range_ = {*lo, *hi > *lo ? *hi : *lo + 1.0f};
  // Label maps keep their classes: nearest; other attributes are interpolated.
  functional_ = upload3D(functional.dimensions(), GL_R32F, GL_RED, values.data(),
                         !isInteger(functional.scalarType()), "uploading the functional volume");
  ++generation_;
  textureFromAnatomicalWorld_ = textureFromIndex(functional.dimensions()) *
                                glm::inverse(functional.worldFromIndex()) *
                                glm::inverse(anatomicalFromFunctional);
  if (colormap_.id()) return;
  // Opaque: the overlay opacity is a uniform, applied where the attribute passes the threshold.
  std::vector<glm::vec4> opaque =
      sampleTransferFunction(transferPreset("pet-hot-metal"), 0.0, 1.0, 256, 0.0, 1.0);
  for (auto& c : opaque) c.a = 1.0f;
  colormap_ = makeTexture();
  glBindTexture(GL_TEXTURE_1D, colormap_.id());
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, 256, 0, GL_RGBA, GL_FLOAT, opaque.data());
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
}

GLuint FunctionalTextures::colormap(const std::optional<ColorTable>& table) {
  if (!table) return colormap_.id();
  if (!custom_ || custom_->rgb != table->rgb) {
    if (!customColormap_.id()) customColormap_ = makeTexture();
    uploadColorTable(customColormap_.id(), *table);
    custom_ = table;
  }
  return customColormap_.id();
}

glm::vec2 FunctionalTextures::window(const ValueWindow& w) const {
  const ValueWindow shown = w.orRange(range_.first, range_.second);
  return {float(shown.low), float(shown.high)};
}

void FunctionalTextures::setUniforms(const ShaderProgram& program, glm::vec2 window,
                                     int classes) const {
  const glm::mat4 functionalFromWorld(textureFromAnatomicalWorld_);
  glUniformMatrix4fv(program.uniform("uFunctionalFromWorld"), 1, GL_FALSE,
                     glm::value_ptr(functionalFromWorld));
  glUniform2f(program.uniform("uFunctionalRange"), window.x, window.y);
  glUniform1i(program.uniform("uFunctionalClasses"), std::max(0, classes));
}

}  // namespace mvw::render::detail
