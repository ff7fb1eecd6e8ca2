// Constants and small helpers shared by every shader.
#ifndef LGH_COMMON_GLSL
#define LGH_COMMON_GLSL

const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;

float saturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 saturate(vec3 x) { return clamp(x, vec3(0.0), vec3(1.0)); }
float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }

#endif
