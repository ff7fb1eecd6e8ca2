#version 450 core
// Test kernel (tests/integration/test_lgh_lighting.cpp): every invocation is one "pixel" that
// streams the same weight list through the reservoir of include/reservoir.glsl, in order, and
// writes the light each of its k samples chose (0xffffffff: none). The test checks the choice
// frequencies against f_i / sum f (chi-square) and the choices against the C++ mirror.

#include "include/reservoir.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Weights { float weights[]; };
layout(std430, binding = 1) writeonly buffer Choices { uint choices[]; };

uniform uint uPixels;
uniform uint uLightCount;
uniform int uSampleCount;
uniform uint uSeed;

void main() {
  uint pixel = gl_GlobalInvocationID.x;
  if (pixel >= uPixels) return;
  uint pixelSeed = reservoirPixelSeed(uSeed, pixel);
  uint chosen[LGH_MAX_SHADOW_SAMPLES];
  for (int s = 0; s < LGH_MAX_SHADOW_SAMPLES; ++s) chosen[s] = 0xffffffffu;
  float runningSum = 0.0;
  for (uint i = 0u; i < uLightCount; ++i) {
    float f = weights[i];
    if (!(f > 0.0)) continue;
    runningSum += f;
    uint mask = reservoirReplaceMask(f, runningSum, reservoirLightSeed(pixelSeed, i), uSampleCount);
    for (int s = 0; s < uSampleCount; ++s) {
      if ((mask & (1u << uint(s))) != 0u) chosen[s] = i;
    }
  }
  for (int s = 0; s < uSampleCount; ++s) choices[pixel * uint(uSampleCount) + uint(s)] = chosen[s];
}
