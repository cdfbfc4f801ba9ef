// The sampling ceiling (issue 53, SampleCeiling): the least a ray caster can do per sample,
// one trilinear fetch of the volume's intensity texture and an add, uSamples per pixel along
// parallel rays through the volume (texture y, as an anterior view's), so that neighbouring
// pixels read neighbouring texels as a ray caster's do. Samples per second of this shader
// are what llvmpipe delivers at most; the modes' figures are taken as a fraction of it.
layout(location = 0) out vec4 fragColor;

uniform sampler3D uIntensity;
uniform vec2 uViewport;
uniform int uSamples;

void main() {
  vec2 p = gl_FragCoord.xy / uViewport;
  float dy = 1.0 / float(uSamples);
  float sum = 0.0;
  for (int k = 0; k < uSamples; ++k)
    sum += textureLod(uIntensity, vec3(p.x, (float(k) + 0.5) * dy, p.y), 0.0).r;
  // Written out, so that the compiler keeps every fetch.
  fragColor = vec4(vec3(sum * dy), 1.0);
}
