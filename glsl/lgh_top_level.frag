#version 450 core
// LGH raster lighting, top level: its (at most 8) grid lights have blending weights that never
// reach 0 with distance, so they are drawn as one full-screen pass over the (tile) atlas rather
// than as light volumes (Lin & Yuksel 2019, Sec. 3.2). Each tile evaluates the top lights that
// interleaving assigns to it, after the light volumes, in buffer order like every other path.
// Inputs/outputs as glsl/lgh_light_volume.frag.

#ifndef LGH_LOCK_MODE
#define LGH_LOCK_MODE 0
#endif
#if LGH_LOCK_MODE == 1
#extension GL_ARB_fragment_shader_interlock : require
layout(pixel_interlock_ordered) in;
#endif

#define LGH_SAMPLE_STORAGE
#define LGH_RASTER_RESERVOIR
#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 atlasPixel = ivec2(gl_FragCoord.xy);
  int tile;
  ivec2 pixel = lghFramePixel(atlasPixel, tile);
  LghFrame frame = lghFrame();
  SurfacePoint s;
  if (!lghInFrame(pixel) || !lghHasLights(frame) || !readSurface(atlasPixel, s)) discard;
  vec3 toViewer = normalize(uCameraPosition - s.position);
  uint first = lghFirstLight(frame);
  uint top = lghTopOffset(frame);
  uint count = min(lghTopCount(frame), 8u);
  vec3 total = vec3(0.0);
  float weights[8];
  for (uint i = 0u; i < count; ++i) {
    weights[i] = 0.0;
    if (!lghLightInTile(top + i, first, tile)) continue;
#ifdef LGH_OVERDRAW
    imageAtomicAdd(uOverdraw, pixel, 1u);
#endif
    GridLight light = gridLights[top + i];
    float blend;
    vec3 radiance = lghGridLightRadiance(s, toViewer, light, frame, blend);
    total += radiance;
    weights[i] = blend > 0.0 ? lghSampleWeight(light, radiance) : 0.0;
  }
  outRadiance = vec4(total, 0.0);
  LGH_INTERLOCK_BEGIN();
  for (uint i = 0u; i < count; ++i) lghReservoirStream(pixel, top + i, weights[i]);
  LGH_INTERLOCK_END();
}
