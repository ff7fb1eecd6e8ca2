// The light paths' constants on Vulkan (glsl/vk/gi_emit.comp, gi_bounce.comp): the loose uniforms
// of the GL shaders (include/gi_sources.glsl's uSourceCount, uSceneSphere, uSceneMin, uSceneMax,
// and each kernel's own) as one push-constant block whose members keep the uniforms' names, so
// that the includes shared with GL read them unchanged. Include it before include/gi_sources.glsl.
// Mirrored by LightPathPushConstants in renderer/src/vk/light_path_tracer.cpp.
#ifndef LGH_LIGHT_PATH_CONSTANTS_GLSL
#define LGH_LIGHT_PATH_CONSTANTS_GLSL

layout(push_constant, std430) uniform LightPathConstants {
  vec4 uSceneSphere;     // xyz: centre, w: radius of the scene's bounding sphere
  vec3 uSceneMin;        // the scene's bounding box
  float uSurfaceOffset;  // how far rays start off a surface
  vec3 uSceneMax;
  uint uSourceCount;
  uint uPathCount;
  uint uSeed;
  uint uEmissionSlots;  // 1: slot 0 of each path holds its emission VPL
  uint uBounce;         // gi_bounce: 1..bounces
  uint uLastBounce;     // gi_bounce: 1: no next ray
  uint uSlot;           // gi_bounce: the VPL slot of this bounce
};

#endif
