// The ray caster's proxy geometry, from gl_VertexID alone (36 vertices, 6 per face of a box):
// the faces of the crop box, slightly enlarged, that face away from the viewer (BoxProxy.h).
// Their projection covers every pixel whose ray can meet the box, so the fragment shader
// runs for those alone; the target is cleared to what a ray that meets nothing shows.
// uFullscreen: vertices 0-2 cover the viewport instead, and the rest collapse.
uniform mat4 uClipFromTexture;
uniform vec3 uProxyMin;  // texture coordinates
uniform vec3 uProxyMax;
uniform int uFaces;      // bit f: draw face f (axis f / 2; even f its low side)
uniform bool uFullscreen;

const ivec2 kCorners[6] =
    ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

void main() {
  if (uFullscreen) {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = gl_VertexID < 3 ? vec4(p * 2.0 - 1.0, 0.0, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  int face = gl_VertexID / 6;
  if (((uFaces >> face) & 1) == 0) {
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);  // a triangle of no area: nothing drawn
    return;
  }
  int axis = face / 2;
  ivec2 uv = kCorners[gl_VertexID % 6];
  vec3 c;
  c[axis] = float(face & 1);
  c[(axis + 1) % 3] = float(uv.x);
  c[(axis + 2) % 3] = float(uv.y);
  gl_Position = uClipFromTexture * vec4(mix(uProxyMin, uProxyMax, c), 1.0);
}
