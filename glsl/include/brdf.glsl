// glTF 2.0 metallic-roughness BRDF (GGX / Trowbridge-Reitz distribution, height-correlated Smith
// visibility, Schlick Fresnel, Lambert diffuse), the one model every lighting pass evaluates.
#ifndef LGH_BRDF_GLSL
#define LGH_BRDF_GLSL

#include "include/common.glsl"

struct SurfacePoint {
  vec3 position;
  vec3 normal;      // unit, facing the viewer
  vec3 baseColor;   // linear
  float metallic;
  float roughness;  // perceptual
  float occlusion;
};

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

// Reflected radiance per unit incident irradiance: BRDF(l, v) * max(N.L, 0).
vec3 evaluateBrdfCosine(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  float NdotL = dot(s.normal, toLight);
  if (NdotL <= 0.0) return vec3(0.0);
  float NdotV = max(dot(s.normal, toViewer), 1e-4);
  vec3 H = normalize(toLight + toViewer);
  float NdotH = saturate(dot(s.normal, H));
  float VdotH = saturate(dot(toViewer, H));
  float alphaRoughness = max(s.roughness * s.roughness, 1e-3);
  vec3 f0 = mix(vec3(0.04), s.baseColor, s.metallic);
  vec3 F = fresnelSchlick(f0, VdotH);
  vec3 diffuse = (vec3(1.0) - F) * (1.0 - s.metallic) * s.baseColor * INV_PI;
  vec3 specular = F * distributionGgx(NdotH, alphaRoughness) *
                  visibilitySmithGgxCorrelated(NdotL, NdotV, alphaRoughness);
  return (diffuse + specular) * NdotL;
}

#endif
