#version 450 core
// LGH raster lighting, light volumes: one grid light per fragment over the (tile) G-buffer. The
// blending weight decides (discard where 0), the shared shading code gives the unshadowed
// contribution, added into the HDR accumulation target by the blend unit; the light is streamed
// into the pixel's shadow-sample reservoir (include/lgh_shading.glsl, include/reservoir.glsl).
// Inputs: tile G-buffer (units 0..3), grid lights, level table, the light index.
// Outputs: radiance (additive), reservoir sum image, shadow-sample buffer, [overdraw counter].

#ifndef LGH_LOCK_MODE
#define LGH_LOCK_MODE 0
#endif
#if LGH_LOCK_MODE == 1
#extension GL_ARB_fragment_shader_interlock : require
layout(pixel_interlock_ordered) in;
#endif
// Back faces pass where they lie behind the surface: the depth test runs before the shader so
// that it culls, and the shader has side effects only for fragments inside the light's sphere.
layout(early_fragment_tests) in;

#define LGH_SAMPLE_STORAGE
#define LGH_RASTER_RESERVOIR
#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

flat in uint vLight;

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 atlasPixel = ivec2(gl_FragCoord.xy);
  int tile;
  ivec2 pixel = lghFramePixel(atlasPixel, tile);
#ifdef LGH_OVERDRAW
  if (lghInFrame(pixel)) imageAtomicAdd(uOverdraw, pixel, 1u);
#endif
  SurfacePoint s;
  if (!readSurface(atlasPixel, s)) discard;
  GridLight light = gridLights[vLight];
  float blend;
  vec3 radiance = lghGridLightRadiance(s, normalize(uCameraPosition - s.position), light,
                                       lghFrame(), blend);
  if (blend <= 0.0) discard;
  outRadiance = vec4(radiance, 0.0);
  float f = lghSampleWeight(light, radiance);
  LGH_INTERLOCK_BEGIN();
  lghReservoirStream(pixel, vLight, f);
  LGH_INTERLOCK_END();
}
