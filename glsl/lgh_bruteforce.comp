#version 450 core
// Brute-force reference of the many-light lighting: every input point light evaluated at every
// pixel with the shading code of the hierarchy's paths (include/lgh_shading.glsl: same BRDF and
// falloff), unshadowed. The singularity clamp is the hierarchy's (d_min = h_1) or the reference's
// own (uMinDistance2 >= 0: a fixed d_min^2, 0 for none; docs/GI.md says why both). The error metrics of the hierarchy (relative RMSE,
// PSNR) are measured against this image. Lights stream through shared memory, a work group (64)
// at a time.
// With LGH_SHADOWED, the shadowed reference: the lights come in chunks of uChunkCount from
// uChunkFirst on, each with a shadow ray per pixel traced by the Vulkan side (visibility bit r:
// light uChunkFirst + r), and every chunk adds onto the image (the first one writes it).
// Inputs: G-buffer (units 0..4), point lights, level table (for h_1 of the clamp), visibility.
// Output: rgba32f radiance, alpha = coverage.

#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"
#ifdef LGH_SHADOWED
#define LGH_READ_VISIBILITY
#include "include/ray_batch.glsl"
uniform uint uChunkFirst;
#endif

// The pass dispatches gl::groups2D work groups: their size is LGH_GROUP_2D's, one light per
// invocation in each batch.
#define GROUP (LGH_GROUP_2D * LGH_GROUP_2D)

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;

layout(std430, binding = LGH_BIND_POINT_LIGHTS) readonly buffer LghPointLights {
  PointLight pointLights[];
};
#ifdef LGH_SHADOWED
layout(rgba32f, binding = LGH_IMAGE_OUTPUT) uniform image2D uOutput;
#else
layout(rgba32f, binding = LGH_IMAGE_OUTPUT) uniform writeonly image2D uOutput;
#endif

uniform uint uLightCount;  // shadowed: the chunk's lights
uniform float uMinDistance2;  // < 0: the hierarchy's clamp h_1^2

shared PointLight s_lights[GROUP];

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  uint tid = gl_LocalInvocationIndex;
  SurfacePoint s;
  bool valid = lghInFrame(pixel) && readSurface(pixel, s);
  vec3 toViewer = valid ? normalize(uCameraPosition - s.position) : vec3(0.0, 0.0, 1.0);
  float minDistance2 = uMinDistance2 >= 0.0 ? uMinDistance2 : lghFrame().minDistance2;
  vec3 radiance = vec3(0.0);
#ifdef LGH_SHADOWED
  uint first = uChunkFirst;
  uint pixelIndex = lghPixelIndex(pixel);
#else
  uint first = 0u;
#endif
  for (uint batch = 0u; batch < uLightCount; batch += GROUP) {
    if (batch + tid < uLightCount) s_lights[tid] = pointLights[first + batch + tid];
    barrier();
    uint count = min(uint(GROUP), uLightCount - batch);
    if (valid) {
      for (uint i = 0u; i < count; ++i) {
#ifdef LGH_SHADOWED
        if (!rayVisible(pixelIndex, int(batch + i))) continue;
#endif
        vec3 offset = s_lights[i].positionPad.xyz - s.position;
        radiance += lghPointRadiance(s, toViewer, offset, s_lights[i].intensityPad.rgb, minDistance2);
      }
    }
    barrier();
  }
  if (!lghInFrame(pixel)) return;
#ifdef LGH_SHADOWED
  if (first > 0u) radiance += imageLoad(uOutput, pixel).rgb;
#endif
  imageStore(uOutput, pixel, vec4(radiance, valid ? 1.0 : 0.0));
}
