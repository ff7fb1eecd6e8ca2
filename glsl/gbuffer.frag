#version 450 core
// G-buffer pass, fragment stage: samples the glTF material (with KHR_texture_transform on every
// texture) and writes the layout documented in include/gbuffer.glsl: the material model, and for
// metallic-roughness materials with KHR_materials_* layers, their parameters.

#include "include/common.glsl"
#include "include/gbuffer_encoding.glsl"

in VertexData {
  vec3 worldPosition;
  vec3 normal;
  vec4 tangent;
  vec2 uv0;
  vec2 uv1;
  vec4 color;
  vec2 sprite;
} vin;

// Texture slots: texture unit = slot; bit (1 << slot) in uTextureMask / uTexCoord1Mask.
#define SLOT_BASE_COLOR 0
#define SLOT_METALLIC_ROUGHNESS 1
#define SLOT_NORMAL 2
#define SLOT_OCCLUSION 3
#define SLOT_EMISSIVE 4
#define SLOT_CLEARCOAT 5
#define SLOT_CLEARCOAT_ROUGHNESS 6
#define SLOT_CLEARCOAT_NORMAL 7
#define SLOT_SHEEN_COLOR 8
#define SLOT_SHEEN_ROUGHNESS 9
#define SLOT_SPECULAR 10
#define SLOT_SPECULAR_COLOR 11
#define SLOT_TRANSMISSION 12
#define SLOT_COUNT 13

layout(binding = SLOT_BASE_COLOR) uniform sampler2D uBaseColorTexture;
layout(binding = SLOT_METALLIC_ROUGHNESS) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = SLOT_NORMAL) uniform sampler2D uNormalTexture;
layout(binding = SLOT_OCCLUSION) uniform sampler2D uOcclusionTexture;
layout(binding = SLOT_EMISSIVE) uniform sampler2D uEmissiveTexture;
layout(binding = SLOT_CLEARCOAT) uniform sampler2D uClearcoatTexture;
layout(binding = SLOT_CLEARCOAT_ROUGHNESS) uniform sampler2D uClearcoatRoughnessTexture;
layout(binding = SLOT_CLEARCOAT_NORMAL) uniform sampler2D uClearcoatNormalTexture;
layout(binding = SLOT_SHEEN_COLOR) uniform sampler2D uSheenColorTexture;
layout(binding = SLOT_SHEEN_ROUGHNESS) uniform sampler2D uSheenRoughnessTexture;
layout(binding = SLOT_SPECULAR) uniform sampler2D uSpecularTexture;
layout(binding = SLOT_SPECULAR_COLOR) uniform sampler2D uSpecularColorTexture;
layout(binding = SLOT_TRANSMISSION) uniform sampler2D uTransmissionTexture;

uniform uint uTextureMask;
uniform uint uTexCoord1Mask;  // bit set: that texture reads TEXCOORD_1
uniform mat3x2 uUvTransform[SLOT_COUNT];  // KHR_texture_transform per slot
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissiveFactor;
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform float uAlphaCutoff;  // < 0: opaque
uniform vec3 uCameraPosition;
uniform uint uModel;         // MATERIAL_MODEL_*
uniform uint uLayers;        // MATERIAL_LAYER_*
uniform bool uPointDisk;     // points: cut the square to a disk
uniform vec3 uClearcoat;     // factor, roughness, normal scale
uniform vec4 uSheen;         // colour rgb, roughness
uniform vec4 uSpecular;      // colour rgb, factor
uniform float uDielectricF0; // ((ior - 1) / (ior + 1))^2
uniform float uTransmission;
uniform vec3 uTransmissionTint;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outMaterial;
layout(location = 4) out vec4 outEmissive;
layout(location = 5) out uvec4 outLayers;

bool hasTexture(int slot) { return (uTextureMask & (1u << uint(slot))) != 0u; }

vec2 uvFor(int slot) {
  vec2 uv = (uTexCoord1Mask & (1u << uint(slot))) != 0u ? vin.uv1 : vin.uv0;
  return uUvTransform[slot] * vec3(uv, 1.0);
}

vec3 perturbedNormal(vec3 geometricNormal, vec3 tangentSpaceNormal, float scale) {
  vec3 t = vin.tangent.xyz - geometricNormal * dot(geometricNormal, vin.tangent.xyz);
  if (dot(t, t) < 1e-12) return geometricNormal;
  t = normalize(t);
  vec3 b = cross(geometricNormal, t) * (vin.tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 n = tangentSpaceNormal * 2.0 - 1.0;
  n.xy *= scale;
  vec3 mapped = normalize(mat3(t, b, geometricNormal) * n);
  return all(isnan(mapped)) ? geometricNormal : mapped;
}

vec3 shadingNormal(vec3 geometricNormal) {
  if (!hasTexture(SLOT_NORMAL)) return geometricNormal;
  return perturbedNormal(geometricNormal, texture(uNormalTexture, uvFor(SLOT_NORMAL)).xyz,
                         uNormalScale);
}

float sampleChannel(int slot, sampler2D map, int channel) {
  return hasTexture(slot) ? texture(map, uvFor(slot))[channel] : 1.0;
}

vec3 sampleColor(int slot, sampler2D map) {
  return hasTexture(slot) ? texture(map, uvFor(slot)).rgb : vec3(1.0);
}

// The layer parameters of this fragment into s (defaults where a layer is off).
void sampleLayers(vec3 geometricNormal, inout SurfacePoint s) {
  if ((uLayers & MATERIAL_LAYER_CLEARCOAT) != 0u) {
    s.clearcoat = uClearcoat.x * sampleChannel(SLOT_CLEARCOAT, uClearcoatTexture, 0);
    s.clearcoatRoughness =
        uClearcoat.y * sampleChannel(SLOT_CLEARCOAT_ROUGHNESS, uClearcoatRoughnessTexture, 1);
    s.clearcoatNormal = hasTexture(SLOT_CLEARCOAT_NORMAL)
                            ? perturbedNormal(geometricNormal,
                                              texture(uClearcoatNormalTexture,
                                                      uvFor(SLOT_CLEARCOAT_NORMAL)).xyz,
                                              uClearcoat.z)
                            : geometricNormal;
  }
  if ((uLayers & MATERIAL_LAYER_SHEEN) != 0u) {
    s.sheenColor = uSheen.rgb * sampleColor(SLOT_SHEEN_COLOR, uSheenColorTexture);
    s.sheenRoughness = uSheen.a * sampleChannel(SLOT_SHEEN_ROUGHNESS, uSheenRoughnessTexture, 3);
  }
  if ((uLayers & MATERIAL_LAYER_SPECULAR) != 0u) {
    s.specularWeight = uSpecular.a * sampleChannel(SLOT_SPECULAR, uSpecularTexture, 3);
    s.dielectricF0 = min(uDielectricF0 * uSpecular.rgb *
                             sampleColor(SLOT_SPECULAR_COLOR, uSpecularColorTexture),
                         vec3(1.0));
  }
  if ((uLayers & MATERIAL_LAYER_TRANSMISSION) != 0u) {
    s.transmission = uTransmission * sampleChannel(SLOT_TRANSMISSION, uTransmissionTexture, 0);
    s.transmissionTint = uTransmissionTint;
  }
}

void main() {
  if (uPointDisk && dot(vin.sprite, vin.sprite) > 1.0) discard;
  vec4 baseColor = uBaseColorFactor * vin.color;
  if (hasTexture(SLOT_BASE_COLOR)) baseColor *= texture(uBaseColorTexture, uvFor(SLOT_BASE_COLOR));
  if (uAlphaCutoff >= 0.0 && baseColor.a < uAlphaCutoff) discard;

  vec3 geometric = normalize(vin.normal);
  if (any(isnan(geometric))) geometric = vec3(0.0, 1.0, 0.0);
  // Shade the side the camera sees (double-sided materials, and mirrored instances).
  if (dot(geometric, uCameraPosition - vin.worldPosition) < 0.0) geometric = -geometric;
  vec3 n = shadingNormal(geometric);

  float metallic = uMetallicFactor;
  float roughness = uRoughnessFactor;
  if (hasTexture(SLOT_METALLIC_ROUGHNESS)) {
    vec4 mr = texture(uMetallicRoughnessTexture, uvFor(SLOT_METALLIC_ROUGHNESS));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  float occlusion = 1.0;
  if (hasTexture(SLOT_OCCLUSION)) {
    occlusion = 1.0 + uOcclusionStrength * (texture(uOcclusionTexture, uvFor(SLOT_OCCLUSION)).r - 1.0);
  }
  vec3 emissive = uEmissiveFactor;
  if (hasTexture(SLOT_EMISSIVE)) emissive *= texture(uEmissiveTexture, uvFor(SLOT_EMISSIVE)).rgb;
  // Unlit: the base colour is what the surface shows, emitted beside its emission (glTF's rule
  // for lines and points without normals; KHR_materials_unlit shows the base colour alone).
  if (uModel == MATERIAL_MODEL_UNLIT) emissive += baseColor.rgb;

  SurfacePoint s = defaultSurface(vin.worldPosition, n, saturate(baseColor.rgb), saturate(metallic),
                                  saturate(roughness), saturate(occlusion));
  uint layers = uModel == MATERIAL_MODEL_METALLIC_ROUGHNESS ? uLayers : 0u;
  if (layers != 0u) sampleLayers(geometric, s);

  outPosition = vec4(vin.worldPosition, 1.0);
  outNormal = vec4(n, 0.0);
  outAlbedo = vec4(s.baseColor, s.occlusion);
  outMaterial = vec4(s.metallic, s.roughness, float(uModel) / 255.0, float(layers) / 255.0);
  outEmissive = vec4(emissive, 0.0);
  outLayers = layers != 0u ? encodeLayers(s) : uvec4(0u);
}
