#include "SegmentTextures.h"

#include <algorithm>
#include <cstdint>

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "TextureUpload.h"

namespace mvw::render::detail {

void SegmentTextures::set(const Volume& masks, const std::vector<glm::vec3>& colours,
                          const glm::dmat4& anatomicalFromSegmentation) {
  count_ = std::min({masks.components(), kMaxSegments, static_cast<int>(colours.size())});
  dims_ = masks.dimensions();
  colours_.assign(colours.begin(), colours.begin() + count_);
  const std::size_t n = masks.voxelCount();
  const auto c = static_cast<std::size_t>(masks.components());
  std::vector<std::uint16_t> bits(n, 0);
  dispatchScalar(masks.scalarType(), [&](auto t) {
    using T = decltype(t);
    const T* p = reinterpret_cast<const T*>(masks.data());
    for (std::size_t v = 0; v < n; ++v)
      for (int s = 0; s < count_; ++s)
        if (p[v * c + static_cast<std::size_t>(s)] != T(0))
          bits[v] = static_cast<std::uint16_t>(bits[v] | (1u << s));
    return 0;
  });
  texture_ = makeTexture();
  glBindTexture(GL_TEXTURE_3D, texture_.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R16UI, dims_.x, dims_.y, dims_.z, 0, GL_RED_INTEGER,
               GL_UNSIGNED_SHORT, bits.data());
  checkGl("uploading the segmentation");
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  setSampling(texture_.id(), GL_TEXTURE_3D, false);  // integer textures: nearest only
  indexFromAnatomicalWorld_ =
      glm::inverse(masks.worldFromIndex()) * glm::inverse(anatomicalFromSegmentation);
}

void SegmentTextures::setUniforms(const ShaderProgram& program, bool show) const {
  const glm::mat4 segmentsFromWorld(indexFromAnatomicalWorld_);
  glUniformMatrix4fv(program.uniform("uSegmentsFromWorld"), 1, GL_FALSE,
                     glm::value_ptr(segmentsFromWorld));
  glUniform3i(program.uniform("uSegmentDims"), dims_.x, dims_.y, dims_.z);
  glUniform1i(program.uniform("uSegmentCount"), show && present() ? count_ : 0);
  if (count_ > 0)
    glUniform3fv(program.uniform("uSegmentColours"), count_, glm::value_ptr(colours_.front()));
}

}  // namespace mvw::render::detail
