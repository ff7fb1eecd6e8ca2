#version 450 core
// Test kernel (tests/integration/test_display_transform.cpp): the display transform of
// include/display_transform.glsl applied to a list of linear values, so that the test can compare
// it with the CPU's lgh::toDisplay8 at chosen values (every sRGB threshold and its float
// neighbours, NaN, infinities, negatives).

#include "include/display_transform.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Values { float values[]; };
layout(std430, binding = 1) writeonly buffer Codes { uint codes[]; };

uniform int uToneMap;
uniform float uExposure;
uniform uint uCount;
uniform bool uAlpha;  // the alpha channel's rounding instead of a colour channel's

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  codes[i] = uAlpha ? lghAlpha8(values[i]) : lghDisplayChannel(values[i], uToneMap, uExposure);
}
