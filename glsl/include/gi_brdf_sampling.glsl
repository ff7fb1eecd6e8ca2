// Sampling the glTF BRDF (include/brdf.glsl) for the path-traced reference's first bounce: one
// sample from a mixture of the cosine lobe and the GGX distribution of normals (Walter et al.
// 2007), weighted by the mixture's density (one-sample multiple importance sampling), so that
// both the diffuse and the glossy pixels converge.
#ifndef LGH_GI_BRDF_SAMPLING_GLSL
#define LGH_GI_BRDF_SAMPLING_GLSL

#include "include/brdf.glsl"
#include "include/gi_random.glsl"

// The chance of sampling the GGX lobe: more on metals, whose reflection is all specular.
float giSpecularChance(SurfacePoint s) { return mix(0.25, 0.9, saturate(s.metallic)); }

float giAlpha(SurfacePoint s) { return max(s.roughness * s.roughness, 1e-3); }

// Density (per solid angle) of the mixture at direction l.
float giBrdfPdf(SurfacePoint s, vec3 toViewer, vec3 l) {
  float cosL = dot(s.normal, l);
  if (cosL <= 0.0) return 0.0;
  vec3 h = normalize(l + toViewer);
  float alpha = giAlpha(s);
  float ggx = distributionGgx(saturate(dot(s.normal, h)), alpha) * saturate(dot(s.normal, h)) /
              max(4.0 * abs(dot(toViewer, h)), 1e-6);
  float chance = giSpecularChance(s);
  return chance * ggx + (1.0 - chance) * cosL * INV_PI;
}

// A direction from the mixture (`u`: three uniform numbers); the zero vector below the surface.
vec3 giSampleBrdf(SurfacePoint s, vec3 toViewer, vec3 u) {
  if (u.z >= giSpecularChance(s)) return giCosineDirection(s.normal, u.xy);
  float alpha = giAlpha(s);
  float phi = 2.0 * PI * u.x;
  float cosTheta = sqrt((1.0 - u.y) / (1.0 + (alpha * alpha - 1.0) * u.y));
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  vec3 t, b;
  giBasis(s.normal, t, b);
  vec3 h = normalize(sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * s.normal);
  vec3 l = reflect(-toViewer, h);
  return dot(l, s.normal) > 0.0 ? l : vec3(0.0);
}

#endif
