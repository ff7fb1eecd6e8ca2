// Analytic lights as the direct-lighting pass and the references read them from an SSBO, with the
// lecture's distance attenuation 1/(kc + kl*d + kq*d^2) and spot effect.
#ifndef LGH_LIGHTS_GLSL
#define LGH_LIGHTS_GLSL

#include "include/common.glsl"

const int LIGHT_DIRECTIONAL = 0;
const int LIGHT_POINT = 1;
const int LIGHT_SPOT = 2;

// std430 layout, mirrored by GpuLight in renderer/src/passes/light_buffer.hpp.
struct Light {
  vec4 positionType;     // xyz position, w type
  vec4 directionRange;   // xyz unit direction the light points to, w range (0: none)
  vec4 colorIntensity;   // rgb colour, w intensity
  vec4 attenuation;      // kc, kl, kq, spot exponent
  vec4 cone;             // cos(inner), cos(outer), shadow size (radius or angular radius), unused
};

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

// Incident irradiance scale (colour * intensity * attenuation * spot) and direction to the light.
vec3 incidentLight(Light light, vec3 position, out vec3 toLight) {
  int type = int(light.positionType.w + 0.5);
  vec3 radiance = light.colorIntensity.rgb * light.colorIntensity.w;
  if (type == LIGHT_DIRECTIONAL) {
    toLight = -light.directionRange.xyz;
    return radiance;
  }
  vec3 offset = light.positionType.xyz - position;
  float d = length(offset);
  toLight = offset / max(d, 1e-6);
  float scale = distanceAttenuation(light, d);
  if (type == LIGHT_SPOT) scale *= spotEffect(light, toLight);
  return radiance * scale;
}

#endif
