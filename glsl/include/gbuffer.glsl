// G-buffer layout: written by gbuffer.frag, read by every lighting pass through these helpers.
//   0 position   RGBA32F  world position xyz, w = 1 + relief self-shadow mask where geometry was
//                         drawn (bit i: analytic light i is hidden by the height field; a float
//                         holds the integers of the first 23 bits exactly), 0 elsewhere
//   1 normal     RGBA16F  world normal xyz (unit, facing the camera), w unused
//   2 albedo     RGBA8    base colour (linear, stored in an sRGB target), a = occlusion
//   3 material   RGBA8    metallic, roughness, model (MATERIAL_MODEL_*, as byte / 255),
//                         layers (MATERIAL_LAYER_* bits, as byte / 255; classic models:
//                         MATERIAL_CLASSIC_* flags)
//   4 emissive   RGBA16F  emitted radiance rgb (unlit surfaces: their colour), a unused
//   6 layers     RGBA32UI the layers' parameters, read only where the layer bits are set:
//                  x  unorm8 x4: clearcoat, clearcoat roughness, sheen roughness, transmission
//                  y  unorm8 x4: sheen colour rgb, specular weight
//                  z  unorm8 x4: sqrt(dielectric F0) rgb, volume tint (grey, see MATERIALS.md)
//                  w  snorm16 x2: clearcoat normal, octahedral
//                The classic models (Phong and up) always write it, with their own meaning:
//                  x  unorm8 x4: ambient colour rgb, unused
//                  y  unorm8 x4: sqrt(specular colour) rgb (Cook-Torrance: sqrt(F0)), unused
//                  z  float: shininess (Phong, Blinn-Phong), sigma (Oren-Nayar), m (Cook-Torrance)
//                  w  RGB9E5: the lights' diffuse + specular terms per vertex (Gouraud) or per
//                     primitive (flat), where MATERIAL_CLASSIC_VERTEX_LIT is set
// Texture unit 5 belongs to the passes (atlas, depth, shadow ratio): the layers sit at unit
// LGH_UNIT_GBUFFER_LAYERS (6).
#ifndef LGH_GBUFFER_GLSL
#define LGH_GBUFFER_GLSL

#include "include/brdf.glsl"
#include "include/gbuffer_encoding.glsl"
#include "include/slots.glsl"

layout(binding = 0) uniform sampler2D gPosition;
layout(binding = 1) uniform sampler2D gNormal;
layout(binding = 2) uniform sampler2D gAlbedo;
layout(binding = 3) uniform sampler2D gMaterial;
layout(binding = 4) uniform sampler2D gEmissive;
layout(binding = LGH_UNIT_GBUFFER_LAYERS) uniform usampler2D gLayers;

// Whether geometry was drawn at `pixel` (readSurface's answer, from the position target alone).
bool surfaceCovered(ivec2 pixel) { return texelFetch(gPosition, pixel, 0).w > 0.5; }

bool readSurface(ivec2 pixel, out SurfacePoint s) {
  vec4 position = texelFetch(gPosition, pixel, 0);
  vec4 albedo = texelFetch(gAlbedo, pixel, 0);
  vec4 material = texelFetch(gMaterial, pixel, 0);
  s = defaultSurface(position.xyz, normalize(texelFetch(gNormal, pixel, 0).xyz), albedo.rgb,
                     material.r, material.g, albedo.a);
  s.model = uint(material.b * 255.0 + 0.5);
  uint flags = uint(material.a * 255.0 + 0.5);
  // Under LGH_BRDF_MODELS / LGH_BRDF_LAYERS (include/brdf.glsl), only what the frame has: the
  // fields of the rest keep defaultSurface()'s constants.
  if (isClassicModel(s.model)) {
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BITS_CLASSIC)
    decodeClassic(texelFetch(gLayers, pixel, 0), flags, s);
#endif
  } else {
    s.layers = flags;
#if LGH_BRDF_LAYERS != 0
    if (s.layers != 0u) decodeLayers(texelFetch(gLayers, pixel, 0), s);
#endif
  }
  s.selfShadowMask = uint(max(position.w - 1.0, 0.0) + 0.5);
  return position.w > 0.5;
}

#endif
