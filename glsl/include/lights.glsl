// Analytic lights as the lighting passes read them from an SSBO, with the lecture's distance
// attenuation 1/(kc + kl*d + kq*d^2), spot effect and per-light ambient, diffuse and specular
// colours (include/light_terms.glsl combines them with the BRDF).
#ifndef LGH_LIGHTS_GLSL
#define LGH_LIGHTS_GLSL

#include "include/common.glsl"
#include "include/slots.glsl"

const int LIGHT_DIRECTIONAL = 0;
const int LIGHT_POINT = 1;
const int LIGHT_SPOT = 2;

// std430 layout, mirrored by GpuLight in renderer/src/passes/light_buffer.hpp.
struct Light {
  vec4 positionType;     // xyz position, w type
  vec4 directionRange;   // xyz unit direction the light points to, w range (0: none)
  vec4 ambient;          // rgb: ambient colour x intensity, w unused
  vec4 diffuse;          // rgb: diffuse colour x intensity (the light's colour unless set)
  vec4 specular;         // rgb: specular colour x intensity (the light's colour unless set)
  vec4 attenuation;      // kc, kl, kq, spot exponent
  vec4 cone;             // cos(inner), cos(outer), shadow size (radius or angular radius), unused
};

#ifdef LGH_LIGHTS_BUFFER
layout(std430, binding = LGH_BIND_LIGHTS) readonly buffer Lights { Light lights[]; };
#endif

float distanceAttenuation(Light light, float d) {
  vec3 k = light.attenuation.xyz;
  float attenuation = 1.0 / max(k.x + k.y * d + k.z * d * d, 1e-6);
  float range = light.directionRange.w;
  if (range > 0.0) {  // glTF's smooth window so the light reaches exactly zero at its range
    float ratio = d / range;
    attenuation *= saturate(1.0 - ratio * ratio * ratio * ratio);
  }
  return attenuation;
}

float spotEffect(Light light, vec3 toLight) {
  float cosAngle = dot(-toLight, light.directionRange.xyz);
  float cosInner = light.cone.x;
  float cosOuter = light.cone.y;
  float falloff = saturate((cosAngle - cosOuter) / max(cosInner - cosOuter, 1e-4));
  float exponent = light.attenuation.w;
  if (exponent > 0.0) falloff *= pow(max(cosAngle, 0.0), exponent);
  return falloff * falloff;
}

// The lecture's 1 / (kc + kl d + kq d^2) x spot effect at `position` (1 for directional lights),
// and the direction to the light.
float lightFalloff(Light light, vec3 position, out vec3 toLight) {
  int type = int(light.positionType.w + 0.5);
  if (type == LIGHT_DIRECTIONAL) {
    toLight = -light.directionRange.xyz;
    return 1.0;
  }
  vec3 offset = light.positionType.xyz - position;
  float d = length(offset);
  toLight = offset / max(d, 1e-6);
  float scale = distanceAttenuation(light, d);
  if (type == LIGHT_SPOT) scale *= spotEffect(light, toLight);
  return scale;
}

#endif
