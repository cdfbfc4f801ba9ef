// Small helpers shared by the shaders.
#ifndef MVW_COMMON_MATH
#define MVW_COMMON_MATH

float mvwSaturate(float x) { return clamp(x, 0.0, 1.0); }

#endif
