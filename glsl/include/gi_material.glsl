// The material of a ray hit, read as the G-buffer reads it (gbuffer.frag): the glTF
// metallic-roughness material's base colour (factor x COLOR_0 x base-colour texture) and
// metallic factor. Packed on the CPU by packGiMaterial (renderer/src/gi/gi_material.cpp): a change
// to how materials are read belongs in those two functions. Approximations (docs/GI.md): the
// base-colour textures come from one array of 256 x 256 downsampled copies, read bilinearly at
// level 0; the metallic-roughness texture and normal maps are not read.
#ifndef LGH_GI_MATERIAL_GLSL
#define LGH_GI_MATERIAL_GLSL

#include "include/common.glsl"
#include "include/slots.glsl"

// std430, mirrored by GiMaterialGpu in renderer/src/gi/gi_material.hpp: 64 bytes.
struct GiMaterial {
  vec4 baseColorFactor;
  vec4 emission;           // rgb: emissive factor x the mean of the emissive texture (linear)
  vec4 params;             // x: metallic factor, y: roughness factor, z: 1 double-sided
  ivec4 baseColorTexture;  // x: layer of uGiAlbedo (-1: none), y: texCoord, z: wrapS, w: wrapT
};

layout(std430, binding = LGH_BIND_GI_MATERIALS) readonly buffer GiMaterials {
  GiMaterial giMaterials[];
};
#ifdef VULKAN
// Vulkan (the light paths, glsl/vk/gi_*.comp) has no texture of them: the same layers as packed
// sRGB RGBA8 texels (renderer/src/gi/albedo_array.hpp), kAlbedoSize^2 per layer, filtered here
// as GL filters uGiAlbedo at level 0 (bilinear, clamped to the edge, decoded before filtering).
#define GI_ALBEDO_SIZE 256
layout(std430, binding = LGH_BIND_GI_ALBEDO_TEXELS) readonly buffer GiAlbedoTexels {
  uint giAlbedoTexels[];
};

vec4 giAlbedoTexel(ivec2 texel, int layer) {
  texel = clamp(texel, ivec2(0), ivec2(GI_ALBEDO_SIZE - 1));
  vec4 encoded = unpackUnorm4x8(
      giAlbedoTexels[(layer * GI_ALBEDO_SIZE + texel.y) * GI_ALBEDO_SIZE + texel.x]);
  vec3 low = encoded.rgb / 12.92;
  vec3 high = pow((encoded.rgb + 0.055) / 1.055, vec3(2.4));
  return vec4(mix(high, low, lessThanEqual(encoded.rgb, vec3(0.04045))), encoded.a);
}

vec4 giAlbedoSample(vec2 uv, int layer) {
  vec2 position = uv * float(GI_ALBEDO_SIZE) - 0.5;
  ivec2 corner = ivec2(floor(position));
  vec2 f = position - vec2(corner);
  vec4 bottom = mix(giAlbedoTexel(corner, layer), giAlbedoTexel(corner + ivec2(1, 0), layer), f.x);
  vec4 top = mix(giAlbedoTexel(corner + ivec2(0, 1), layer),
                 giAlbedoTexel(corner + ivec2(1, 1), layer), f.x);
  return mix(bottom, top, f.y);
}
#else
layout(binding = LGH_UNIT_GI_ALBEDO) uniform sampler2DArray uGiAlbedo;

vec4 giAlbedoSample(vec2 uv, int layer) { return textureLod(uGiAlbedo, vec3(uv, float(layer)), 0.0); }
#endif

// A glTF sampler's wrap mode (GL enum) applied to one texture coordinate: into [0, 1].
float giWrap(float x, int mode) {
  if (mode == 0x812F) return clamp(x, 0.0, 1.0);  // GL_CLAMP_TO_EDGE
  if (mode == 0x8370) {                            // GL_MIRRORED_REPEAT
    float m = mod(x, 2.0);
    return m > 1.0 ? 2.0 - m : m;
  }
  return x - floor(x);  // GL_REPEAT
}

// The base colour (linear RGB, alpha) at a surface point.
vec4 giBaseColor(GiMaterial material, vec2 uv0, vec2 uv1, vec4 vertexColor) {
  vec4 color = material.baseColorFactor * vertexColor;
  ivec4 texture = material.baseColorTexture;
  if (texture.x >= 0) {
    vec2 uv = texture.y == 1 ? uv1 : uv0;
    uv = vec2(giWrap(uv.x, texture.z), giWrap(uv.y, texture.w));
    color *= giAlbedoSample(uv, texture.x);
  }
  return color;
}

// What a diffuse bounce reflects: the Lambert lobe's colour, base colour x (1 - metallic) (the
// diffuse term of include/brdf.glsl without its Fresnel weight); metals reflect no diffuse light.
vec3 giDiffuseAlbedo(GiMaterial material, vec4 baseColor) {
  return saturate(baseColor.rgb) * (1.0 - saturate(material.params.x));
}

#endif
