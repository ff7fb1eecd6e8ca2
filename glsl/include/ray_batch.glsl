// The shadow-ray batch as the frame's GL passes see it (the Vulkan side traces it; see
// renderer/src/vk/shadow_tracer.hpp for the layout): per pixel an origin, per pixel and ray a
// target, per pixel and 32 rays a word of visibility bits. Rays of a pixel come in this order:
// uLightSamples rays for each of the first uShadowedLights direct lights, then the LGH's k samples.
#ifndef LGH_RAY_BATCH_GLSL
#define LGH_RAY_BATCH_GLSL

#include "include/slots.glsl"

// A pass compiled for the frame's layout (passes/light_loops.hpp) has the first two as constants,
// so that its loops over the lights unroll.
#ifdef LGH_SHADOWED_LIGHTS
#define uShadowedLights LGH_SHADOWED_LIGHTS
#define uLightSamples LGH_LIGHT_SAMPLES
#else
uniform int uShadowedLights;  // direct lights with shadow rays (the first ones); 0: unshadowed
uniform int uLightSamples;    // rays per shadowed direct light
#endif
uniform int uRaysPerPixel;
uniform int uVisibilityWords;  // (uRaysPerPixel + 31) / 32

#ifdef LGH_READ_VISIBILITY
layout(std430, binding = LGH_BIND_RAY_VISIBILITY) readonly buffer ShadowVisibility {
  uint visibility[];
};

bool rayVisible(uint pixelIndex, int ray) {
  uint word = visibility[pixelIndex * uint(uVisibilityWords) + uint(ray / 32)];
  return (word & (1u << uint(ray % 32))) != 0u;
}

// The fraction of `count` rays from `first` on that reached their end.
float visibleFraction(uint pixelIndex, int first, int count) {
  int visible = 0;
  for (int ray = first; ray < first + count; ++ray) visible += rayVisible(pixelIndex, ray) ? 1 : 0;
  return float(visible) / float(max(count, 1));
}

// Visibility of direct light `light` at a pixel: 1 for lights without shadow rays.
float directLightVisibility(uint pixelIndex, int light) {
  if (light >= uShadowedLights) return 1.0;
  return visibleFraction(pixelIndex, light * uLightSamples, uLightSamples);
}
#endif

#endif
