#version 450 core
// Path-traced reference, end of an iteration: each pixel adds what its paths gathered to its sum
// (alpha: the pixel's coverage).

#include "include/gbuffer.glsl"
#include "include/gi_camera_paths.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = LGH_BIND_GI_RADIANCE) buffer Radiance { vec4 radianceSums[]; };

uniform ivec2 uFrameSize;

void main() {
  uint pixelIndex = cameraPathIndex();
  uint pixels = uint(uFrameSize.x) * uint(uFrameSize.y);
  if (pixelIndex >= pixels) return;
  vec3 sum = vec3(0.0);
  for (uint s = 0u; s < uSamples; ++s) sum += cameraPaths[pixelIndex * uSamples + s].radiance.rgb;
  ivec2 pixel = ivec2(int(pixelIndex % uint(uFrameSize.x)), int(pixelIndex / uint(uFrameSize.x)));
  float covered = texelFetch(gPosition, pixel, 0).w > 0.5 ? 1.0 : 0.0;
  radianceSums[pixelIndex] += vec4(sum, 0.0);
  radianceSums[pixelIndex].a = covered;
}
