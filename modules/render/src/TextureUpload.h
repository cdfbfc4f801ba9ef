#pragma once
// What every texture upload of the ray caster shares (internal to mvw_render): volumes as
// float texels, clamped 3D textures, GL error checks that name what was being done.
#include <vector>

#include <glad/gl.h>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "GlObjects.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Volume.h"

namespace mvw::render::detail {

// Values of component 0 as float, in the volume's physical unit.
std::vector<float> valuesOf(const Volume& volume);

// Throws mvw::Error naming `what` if the GL reported an error (out of memory in its own words:
// the usual way a volume too large for the GL shows).
void checkGl(const char* what);

// Linear or nearest minification and magnification for the texture bound to `target`.
void setSampling(GLuint texture, GLenum target, bool linear);

// A 3D float texture, clamped at the edges: the volume, its gradient, the functional volume.
Texture upload3D(glm::ivec3 dims, GLint internalFormat, GLenum format, const float* data,
                 bool linear, const char* what);
// The same for texels of any `type`; data null allocates the texture (filled later, slab by
// slab, with glTexSubImage3D).
Texture upload3D(glm::ivec3 dims, GLint internalFormat, GLenum format, GLenum type,
                 const void* data, bool linear, const char* what);

// A colour map's 256 entries as a 1D RGBA8 texture, nearest, clamped (texelFetch or u in 0..1).
void uploadColorTable(GLuint texture, const ColorTable& table);

// Index to texture coordinates of a dims-sized 3D texture: texel centres at (i + 0.5) / n.
glm::dmat4 textureFromIndex(glm::ivec3 dims);

}  // namespace mvw::render::detail
