// Shell fragments. MVW_SHELL_MAX: discrete maximum rendering, eq. (4) with the section 2.3
// transform: the key phi_i (beta0 + a z + b) (beta_m = 1) is written as depth so that the
// depth test performs the maximum over shells (smaller depth = larger key; equal keys go to
// the nearer fragment). MVW_SHELL_SUM: approximate summation (section 2.4), each shell's
// nearest intersection weighted 1/n into a float accumulation buffer. MVW_SHELL_LIT: the
// shells as lit isosurfaces (only the outermost is seen).
in float vZ;
in vec3 vNormal;

uniform float uEmission;   // phi_i of this shell, 0..1
uniform vec3 uCue;         // beta0, a, b
uniform float uKeyMax;     // largest possible key, for the depth encoding
uniform float uWeight;     // summation: 1 / n
uniform vec3 uForward;
uniform vec4 uLight;       // ambient, diffuse, specular, shininess

layout(location = 0) out vec4 fragColor;
layout(location = 1) out float fragDepth;

void main() {
  float key = uEmission * (uCue.x + uCue.y * vZ + uCue.z);
#if defined(MVW_SHELL_MAX)
  gl_FragDepth = 0.999 * (1.0 - clamp(key / uKeyMax, 0.0, 1.0)) + 0.001 * (1.0 - vZ);
  fragColor = vec4(vec3(key), 1.0);
#elif defined(MVW_SHELL_SUM)
  fragColor = vec4(vec3(key * uWeight), 1.0);
#else
  vec3 n = normalize(vNormal);
  if (dot(n, uForward) > 0.0) n = -n;
  float diffuse = max(dot(n, -uForward), 0.0);
  float specular = pow(diffuse, uLight.w);
  fragColor = vec4(vec3(uEmission) * (uLight.x + uLight.y * diffuse) + vec3(uLight.z * specular), 1.0);
#endif
  fragDepth = -1.0;
}
