#version 450 core
// LGH shadow ratio: per pixel the mean visibility of its k shadow samples (Sec. 3.3: with
// importance-sampled lights, the mean visibility is the shadow ratio estimator of Heitz et al.
// 2018; include/reservoir.glsl derives it). Samples the reservoir left empty cast no ray and do
// not count; a pixel with none keeps ratio 1 (no LGH light reaches it).
// Inputs: visibility bits, the LGH samples. Output: r16f ratio image.

#define LGH_READ_VISIBILITY
#include "include/ray_batch.glsl"

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;

layout(std430, binding = LGH_BIND_SAMPLES) readonly buffer LghSamples { vec4 lghSamples[]; };
layout(r16f, binding = LGH_IMAGE_SHADOW_RATIO) uniform writeonly image2D uRatio;

uniform ivec2 uFrameSize;
uniform int uLghSampleCount;
uniform int uFirstLghRay;  // uShadowedLights * uLightSamples

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, uFrameSize))) return;
  uint pixelIndex = uint(pixel.y) * uint(uFrameSize.x) + uint(pixel.x);
  int valid = 0;
  int visible = 0;
  for (int k = 0; k < uLghSampleCount; ++k) {
    if (lghSamples[pixelIndex * uint(uLghSampleCount) + uint(k)].w <= 0.0) continue;
    ++valid;
    visible += rayVisible(pixelIndex, uFirstLghRay + k) ? 1 : 0;
  }
  float ratio = valid > 0 ? float(visible) / float(valid) : 1.0;
  imageStore(uRatio, pixel, vec4(ratio));
}
