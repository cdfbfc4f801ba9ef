// A flat colour: the smallest program, used by the GL layer's own tests.
#include "common/math.glsl"

uniform vec4 uColor;
out vec4 fragColor;

void main() { fragColor = vec4(mvwSaturate(uColor.r), mvwSaturate(uColor.g), mvwSaturate(uColor.b), uColor.a); }
