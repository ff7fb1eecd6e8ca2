// G-buffer layout: written by gbuffer.frag, read by every lighting pass through these helpers.
//   0 position   RGBA32F  world position xyz, w = 1 where geometry was drawn
//   1 normal     RGBA16F  world normal xyz (unit, facing the camera), w unused
//   2 albedo     RGBA8    base colour (linear, stored in an sRGB target), a = occlusion
//   3 material   RGBA8    metallic, roughness, unused, unused
//   4 emissive   RGBA16F  emitted radiance rgb
#ifndef LGH_GBUFFER_GLSL
#define LGH_GBUFFER_GLSL

#include "include/brdf.glsl"

layout(binding = 0) uniform sampler2D gPosition;
layout(binding = 1) uniform sampler2D gNormal;
layout(binding = 2) uniform sampler2D gAlbedo;
layout(binding = 3) uniform sampler2D gMaterial;
layout(binding = 4) uniform sampler2D gEmissive;

bool readSurface(ivec2 pixel, out SurfacePoint s) {
  vec4 position = texelFetch(gPosition, pixel, 0);
  s.position = position.xyz;
  s.normal = normalize(texelFetch(gNormal, pixel, 0).xyz);
  vec4 albedo = texelFetch(gAlbedo, pixel, 0);
  s.baseColor = albedo.rgb;
  s.occlusion = albedo.a;
  vec4 material = texelFetch(gMaterial, pixel, 0);
  s.metallic = material.r;
  s.roughness = material.g;
  return position.w > 0.5;
}

#endif
