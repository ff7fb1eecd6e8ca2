#version 450 core
// Brute-force reference of the many-light lighting: every input point light evaluated at every
// pixel with the shading code of the hierarchy's paths (include/lgh_shading.glsl: same BRDF,
// falloff and singularity clamp), unshadowed. The error metrics of the hierarchy (relative RMSE,
// PSNR) are measured against this image. The shadowed reference traces a ray per light and pixel
// (passes/lgh_bruteforce_pass.hpp).
// Lights stream through shared memory in batches of 64.
// Inputs: G-buffer (units 0..4), point lights, level table (for h_1 of the clamp).
// Output: rgba32f radiance, alpha = coverage.

#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

#define GROUP 64

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = LGH_BIND_POINT_LIGHTS) readonly buffer LghPointLights {
  PointLight pointLights[];
};
layout(rgba32f, binding = LGH_IMAGE_OUTPUT) uniform writeonly image2D uOutput;

uniform uint uLightCount;

shared PointLight s_lights[GROUP];

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  uint tid = gl_LocalInvocationIndex;
  SurfacePoint s;
  bool valid = lghInFrame(pixel) && readSurface(pixel, s);
  vec3 toViewer = valid ? normalize(uCameraPosition - s.position) : vec3(0.0, 0.0, 1.0);
  float minDistance2 = lghFrame().minDistance2;
  vec3 radiance = vec3(0.0);
  for (uint batch = 0u; batch < uLightCount; batch += GROUP) {
    if (batch + tid < uLightCount) s_lights[tid] = pointLights[batch + tid];
    barrier();
    uint count = min(uint(GROUP), uLightCount - batch);
    if (valid) {
      for (uint i = 0u; i < count; ++i) {
        vec3 offset = s_lights[i].positionPad.xyz - s.position;
        radiance += lghPointRadiance(s, toViewer, offset, s_lights[i].intensityPad.rgb, minDistance2);
      }
    }
    barrier();
  }
  if (lghInFrame(pixel)) imageStore(uOutput, pixel, vec4(radiance, valid ? 1.0 : 0.0));
}
