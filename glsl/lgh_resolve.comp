#version 450 core
// LGH raster lighting, last step: turns the pending shadow samples (light index, f_i) into their
// final form (jittered position, weight F / (k f_i)) and, without interleaving, copies the fp32
// accumulation target into the rgba16f indirect target (the compute path does both itself).
// Defines: LGH_RESOLVE_COPY (copy the radiance too).
// Inputs: reservoir sum image, shadow-sample buffer, grid lights, [accumulation, G-buffer].
// Outputs: shadow-sample buffer, [indirect target].

#define LGH_SAMPLE_STORAGE
#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef LGH_RESOLVE_COPY
layout(binding = LGH_UNIT_PASS_INPUT) uniform sampler2D uAccumulation;
layout(rgba16f, binding = LGH_IMAGE_OUTPUT) uniform writeonly image2D uOutput;
#endif

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!lghInFrame(pixel)) return;
  uint pixelIndex = lghPixelIndex(pixel);
  uint pixelSeed = reservoirPixelSeed(uSeed, pixelIndex);
  float runningSum = imageLoad(uReservoirSum, pixel).r;
  uint base = pixelIndex * uint(uSampleCount);
  for (int s = 0; s < uSampleCount; ++s) {
    vec4 pending = shadowSamples[base + uint(s)];
    shadowSamples[base + uint(s)] =
        lghFinalSample(pixelSeed, pending, runningSum, uint(s), texelFetch(gPosition, pixel, 0).xyz);
  }
#ifdef LGH_RESOLVE_COPY
  float coverage = texelFetch(gPosition, pixel, 0).w > 0.5 ? 1.0 : 0.0;
  imageStore(uOutput, pixel, vec4(texelFetch(uAccumulation, pixel, 0).rgb, coverage));
#endif
}
