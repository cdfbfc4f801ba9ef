// The functional attribute (0..1 through the view's window or classes) at the centres of one
// slice of anatomical voxels: the renderer writes it into the gradient texture's alpha with
// an alpha-only colour mask, so glyph shading reads beta with the gradient in the ray loop
// (where that alpha holds the intensity or there is no gradient texture, into the red of an
// attribute volume of its own).
#include "common/functional.glsl"

uniform mat4 uWorldFromIndex;  // anatomical voxel index -> world (LPS mm)
uniform float uSlice;          // the slice (k) being written

layout(location = 0) out vec4 fragColor;

void main() {
  vec3 world = (uWorldFromIndex * vec4(gl_FragCoord.xy - 0.5, uSlice, 1.0)).xyz;
  float beta = functionalFraction(world);
  fragColor = vec4(beta, 0.0, 0.0, beta);  // the colour mask keeps the target's channel
}
