// The BRDF library every lighting pass evaluates (direct lighting, the LGH paths, the brute-force
// reference): evaluateBrdfCosine() switches on the surface's material model
// (include/material_models.glsl). The glTF model is metallic-roughness (GGX / Trowbridge-Reitz
// distribution, height-correlated Smith visibility, Schlick Fresnel, Lambert diffuse) with the
// KHR_materials_* layers of docs/MATERIALS.md: specular/ior (the dielectric Fresnel), sheen
// (Charlie distribution, Neubelt visibility), clearcoat (a GGX coat over the base) and
// transmission (approximated as diffuse transmission: light from behind the surface).
#ifndef LGH_BRDF_GLSL
#define LGH_BRDF_GLSL

#include "include/common.glsl"
#include "include/material_models.glsl"

struct SurfacePoint {
  vec3 position;
  vec3 normal;      // unit, facing the viewer
  vec3 baseColor;   // linear
  float metallic;
  float roughness;  // perceptual
  float occlusion;
  uint model;   // MATERIAL_MODEL_*
  uint layers;  // MATERIAL_LAYER_* bits; the fields below hold their defaults where unset
  vec3 dielectricF0;     // 0.04: IOR 1.5
  float specularWeight;  // KHR_materials_specular's specular (the dielectric F90)
  float clearcoat;
  float clearcoatRoughness;
  vec3 clearcoatNormal;  // unit, facing the viewer
  vec3 sheenColor;
  float sheenRoughness;
  float transmission;
  vec3 transmissionTint;  // KHR_materials_volume's attenuation over the thickness
};

// A surface with the defaults of every layer (plain metallic-roughness).
SurfacePoint defaultSurface(vec3 position, vec3 normal, vec3 baseColor, float metallic,
                            float roughness, float occlusion) {
  return SurfacePoint(position, normal, baseColor, metallic, roughness, occlusion,
                      MATERIAL_MODEL_METALLIC_ROUGHNESS, 0u, vec3(0.04), 1.0, 0.0, 0.0, normal,
                      vec3(0.0), 0.0, 0.0, vec3(1.0));
}

float distributionGgx(float NdotH, float alphaRoughness) {
  float a2 = alphaRoughness * alphaRoughness;
  float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

float visibilitySmithGgxCorrelated(float NdotL, float NdotV, float alphaRoughness) {
  float a2 = alphaRoughness * alphaRoughness;
  float ggxV = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
  float ggxL = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
  float sum = ggxV + ggxL;
  return sum > 0.0 ? 0.5 / sum : 0.0;
}

vec3 fresnelSchlick(vec3 f0, float VdotH) {
  return f0 + (vec3(1.0) - f0) * pow(1.0 - saturate(VdotH), 5.0);
}

// Charlie sheen distribution (Estevez & Kulla 2017), as KHR_materials_sheen specifies.
float distributionCharlie(float NdotH, float sheenRoughness) {
  float alpha = max(sheenRoughness * sheenRoughness, 1e-3);
  float invAlpha = 1.0 / alpha;
  float sin2 = max(1.0 - NdotH * NdotH, 0.0);
  return (2.0 + invAlpha) * pow(sin2, invAlpha * 0.5) / (2.0 * PI);
}

// Neubelt & Pettineo's visibility for sheen: cheap, and bounded at grazing angles.
float visibilityNeubelt(float NdotL, float NdotV) {
  return saturate(1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV)));
}

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// glTF metallic-roughness with its layers. For a surface without layers this is exactly the
// plain glTF BRDF (dielectricF0 = 0.04, specularWeight = 1).
vec3 metallicRoughnessBrdfCosine(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  float NdotL = dot(s.normal, toLight);
  vec3 transmitted = vec3(0.0);
  if ((s.layers & MATERIAL_LAYER_TRANSMISSION) != 0u && NdotL < 0.0) {
    // Light from behind a transmissive surface: the transmitted share of the diffuse lobe.
    transmitted = s.transmission * (1.0 - s.metallic) * s.baseColor * s.transmissionTint *
                  INV_PI * -NdotL;
  }
  if (NdotL <= 0.0) return transmitted;
  float NdotV = max(dot(s.normal, toViewer), 1e-4);
  vec3 H = normalize(toLight + toViewer);
  float NdotH = saturate(dot(s.normal, H));
  float VdotH = saturate(dot(toViewer, H));
  float alphaRoughness = max(s.roughness * s.roughness, 1e-3);
  vec3 f0 = mix(s.dielectricF0, s.baseColor, s.metallic);
  vec3 F = fresnelSchlick(f0, VdotH) * mix(s.specularWeight, 1.0, s.metallic);
  float diffuseShare = (1.0 - s.metallic) * (1.0 - s.transmission);
  vec3 diffuse = (vec3(1.0) - F) * diffuseShare * s.baseColor * INV_PI;
  vec3 specular = F * distributionGgx(NdotH, alphaRoughness) *
                  visibilitySmithGgxCorrelated(NdotL, NdotV, alphaRoughness);
  vec3 base = (diffuse + specular) * NdotL;
  if ((s.layers & MATERIAL_LAYER_SHEEN) != 0u) {
    // Energy the sheen takes from the base: its directional albedo, approximated by a constant
    // fraction of the sheen colour (docs/MATERIALS.md).
    vec3 sheen = s.sheenColor * distributionCharlie(NdotH, s.sheenRoughness) *
                 visibilityNeubelt(NdotL, NdotV);
    base = base * (1.0 - 0.157 * maxComponent(s.sheenColor)) + sheen * NdotL;
  }
  if ((s.layers & MATERIAL_LAYER_CLEARCOAT) != 0u) {
    float ccNdotL = dot(s.clearcoatNormal, toLight);
    float ccNdotV = max(dot(s.clearcoatNormal, toViewer), 1e-4);
    float ccNdotH = saturate(dot(s.clearcoatNormal, H));
    float ccAlpha = max(s.clearcoatRoughness * s.clearcoatRoughness, 1e-3);
    float Fc = fresnelSchlick(vec3(0.04), VdotH).x * s.clearcoat;
    float coat = ccNdotL > 0.0 ? Fc * distributionGgx(ccNdotH, ccAlpha) *
                                     visibilitySmithGgxCorrelated(ccNdotL, ccNdotV, ccAlpha) *
                                     ccNdotL
                               : 0.0;
    base = base * (1.0 - Fc) + vec3(coat);
  }
  return base + transmitted;
}

// Reflected radiance per unit incident irradiance: BRDF(l, v) * max(N.L, 0), for the surface's
// material model. Unlit surfaces reflect nothing: their colour is emitted (the G-buffer pass
// writes it to the emissive target).
vec3 evaluateBrdfCosine(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  switch (s.model) {
    case MATERIAL_MODEL_UNLIT:
      return vec3(0.0);
    default:
      return metallicRoughnessBrdfCosine(s, toViewer, toLight);
  }
}

// What the constant ambient term lights: the diffuse colour with its occlusion, none for unlit.
vec3 ambientResponse(SurfacePoint s) {
  return s.model == MATERIAL_MODEL_UNLIT ? vec3(0.0) : s.baseColor * s.occlusion;
}

#endif
