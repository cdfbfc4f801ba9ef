// Isosurface shells for the discrete maximum projection (Heidrich et al. 1995): world-space
// triangles, plus the paper's projector parameter z (0 at the background side of the
// volume's bounding sphere, 1 at the image side; the same z the ray caster uses).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uClipFromWorld;
uniform vec3 uForward;          // line of sight (orthographic: the same for every projector)
uniform vec4 uBoundingSphere;   // centre (world mm), radius

out float vZ;
out vec3 vNormal;

void main() {
  gl_Position = uClipFromWorld * vec4(aPosition, 1.0);
  vZ = 0.5 - 0.5 * dot(aPosition - uBoundingSphere.xyz, uForward) / uBoundingSphere.w;
  vNormal = aNormal;
}
