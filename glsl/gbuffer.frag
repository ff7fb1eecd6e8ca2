#version 450 core
// G-buffer pass, fragment stage: samples the glTF material and writes the layout documented in
// include/gbuffer.glsl.

#include "include/common.glsl"

in VertexData {
  vec3 worldPosition;
  vec3 normal;
  vec4 tangent;
  vec2 uv0;
  vec2 uv1;
  vec4 color;
} vin;

layout(binding = 0) uniform sampler2D uBaseColorTexture;
layout(binding = 1) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = 2) uniform sampler2D uNormalTexture;
layout(binding = 3) uniform sampler2D uOcclusionTexture;
layout(binding = 4) uniform sampler2D uEmissiveTexture;

const uint HAS_BASE_COLOR = 1u;
const uint HAS_METALLIC_ROUGHNESS = 2u;
const uint HAS_NORMAL = 4u;
const uint HAS_OCCLUSION = 8u;
const uint HAS_EMISSIVE = 16u;

uniform uint uTextureMask;
uniform uint uTexCoord1Mask;  // bit set: that texture reads TEXCOORD_1
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissiveFactor;
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform float uAlphaCutoff;  // < 0: opaque
uniform vec3 uCameraPosition;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outMaterial;
layout(location = 4) out vec4 outEmissive;

vec2 uvFor(uint textureBit) { return (uTexCoord1Mask & textureBit) != 0u ? vin.uv1 : vin.uv0; }

vec3 shadingNormal(vec3 geometricNormal) {
  if ((uTextureMask & HAS_NORMAL) == 0u) return geometricNormal;
  vec3 t = vin.tangent.xyz - geometricNormal * dot(geometricNormal, vin.tangent.xyz);
  if (dot(t, t) < 1e-12) return geometricNormal;
  t = normalize(t);
  vec3 b = cross(geometricNormal, t) * (vin.tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 n = texture(uNormalTexture, uvFor(HAS_NORMAL)).xyz * 2.0 - 1.0;
  n.xy *= uNormalScale;
  vec3 mapped = normalize(mat3(t, b, geometricNormal) * n);
  return all(isnan(mapped)) ? geometricNormal : mapped;
}

void main() {
  vec4 baseColor = uBaseColorFactor * vin.color;
  if ((uTextureMask & HAS_BASE_COLOR) != 0u) baseColor *= texture(uBaseColorTexture, uvFor(HAS_BASE_COLOR));
  if (uAlphaCutoff >= 0.0 && baseColor.a < uAlphaCutoff) discard;

  vec3 n = normalize(vin.normal);
  if (any(isnan(n))) n = vec3(0.0, 1.0, 0.0);
  // Shade the side the camera sees (double-sided materials, and mirrored instances).
  if (dot(n, uCameraPosition - vin.worldPosition) < 0.0) n = -n;
  n = shadingNormal(n);

  float metallic = uMetallicFactor;
  float roughness = uRoughnessFactor;
  if ((uTextureMask & HAS_METALLIC_ROUGHNESS) != 0u) {
    vec4 mr = texture(uMetallicRoughnessTexture, uvFor(HAS_METALLIC_ROUGHNESS));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  float occlusion = 1.0;
  if ((uTextureMask & HAS_OCCLUSION) != 0u) {
    occlusion = 1.0 + uOcclusionStrength * (texture(uOcclusionTexture, uvFor(HAS_OCCLUSION)).r - 1.0);
  }
  vec3 emissive = uEmissiveFactor;
  if ((uTextureMask & HAS_EMISSIVE) != 0u) emissive *= texture(uEmissiveTexture, uvFor(HAS_EMISSIVE)).rgb;

  outPosition = vec4(vin.worldPosition, 1.0);
  outNormal = vec4(n, 0.0);
  outAlbedo = vec4(saturate(baseColor.rgb), saturate(occlusion));
  outMaterial = vec4(saturate(metallic), saturate(roughness), 0.0, 0.0);
  outEmissive = vec4(emissive, 0.0);
}
