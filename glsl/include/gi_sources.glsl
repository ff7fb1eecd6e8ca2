// The light sources of the light paths and of the reference's next-event estimation
// (docs/GI.md): the frame's analytic lights (include/lights.glsl, the direct lighting's own
// buffer) and the scene's emissive triangles, each with its power and a cumulative selection
// probability (renderer/src/gi/gi_sources.hpp builds the table, mirrored there). A path picks a
// source with probability proportional to the luminance of its power.
#ifndef LGH_GI_SOURCES_GLSL
#define LGH_GI_SOURCES_GLSL

#include "include/gi_random.glsl"
#include "include/lights.glsl"
#include "include/slots.glsl"

#define GI_SOURCE_LIGHT 0
#define GI_SOURCE_TRIANGLE 1

struct GiSource {  // 112 bytes
  ivec4 info;      // x: kind (GI_SOURCE_*), y: light: its index in giLights, z: triangle: 1 double-sided
  vec4 vertex0;    // triangle: vertex 0 (world); w: its area
  vec4 edge1;      // triangle: vertex 1 - vertex 0
  vec4 edge2;      // triangle: vertex 2 - vertex 0
  vec4 normal;     // triangle: unit normal of its counter-clockwise side
  vec4 radiance;   // triangle: emitted radiance (rgb)
  vec4 power;      // rgb: emitted power; w: cumulative selection probability, up to and including it
};

layout(std430, binding = LGH_BIND_GI_SOURCES) readonly buffer GiSources { GiSource giSources[]; };
layout(std430, binding = LGH_BIND_GI_LIGHTS) readonly buffer GiFrameLights { Light giLights[]; };

uniform uint uSourceCount;
uniform vec4 uSceneSphere;  // xyz: centre, w: radius of the scene's bounding sphere

// Directional lights shine through a disk of the scene's radius, this far upstream of its centre
// (in radii): outside the scene, so every path starts in the open.
const float GI_SUN_DISTANCE = 2.0;
const float GI_FAR = 1e30;

uint giPickSource(float u) {
  uint low = 0u;
  uint high = uSourceCount - 1u;
  while (low < high) {
    uint middle = (low + high) / 2u;
    if (u < giSources[middle].power.w) {
      high = middle;
    } else {
      low = middle + 1u;
    }
  }
  return low;
}

float giSourceProbability(uint index) {
  return giSources[index].power.w - (index > 0u ? giSources[index - 1u].power.w : 0.0);
}

int giLightType(Light light) { return int(light.positionType.w + 0.5); }

// The start of one light path.
struct GiEmission {
  vec3 origin;
  vec3 direction;  // unit
  float tMax;
  vec3 flux;       // the path's flux: power / (selection probability x paths)
  bool fromTriangle;
  vec3 normal;     // triangle: the emitting side
};

// `pathShare`: 1 / (number of paths); `u`: four uniform numbers, `v`: two more.
GiEmission giEmit(uint index, float pathShare, vec4 u, vec2 v) {
  GiSource source = giSources[index];
  GiEmission emission;
  emission.flux = source.power.rgb * (pathShare / max(giSourceProbability(index), 1e-30));
  emission.fromTriangle = source.info.x == GI_SOURCE_TRIANGLE;
  emission.normal = vec3(0.0, 1.0, 0.0);
  emission.tMax = GI_FAR;
  if (emission.fromTriangle) {
    vec2 b = giTriangleBarycentrics(u.xy);
    vec3 n = source.normal.xyz;
    if (source.info.z != 0 && v.x < 0.5) n = -n;
    emission.origin = source.vertex0.xyz + b.x * source.edge1.xyz + b.y * source.edge2.xyz;
    emission.normal = n;
    emission.direction = giCosineDirection(n, u.zw);
    return emission;
  }
  Light light = giLights[source.info.y];
  int type = giLightType(light);
  if (type == LIGHT_DIRECTIONAL) {
    vec3 direction = normalize(light.directionRange.xyz);
    vec3 t, b;
    giBasis(direction, t, b);
    float r = uSceneSphere.w * sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    emission.origin = uSceneSphere.xyz - direction * (GI_SUN_DISTANCE * uSceneSphere.w) +
                      r * (cos(phi) * t + sin(phi) * b);
    emission.direction = direction;
    return emission;
  }
  emission.origin = light.positionType.xyz;
  float range = light.directionRange.w;
  if (range > 0.0) emission.tMax = range;
  if (type == LIGHT_SPOT) {
    emission.direction = giConeDirection(normalize(light.directionRange.xyz), light.cone.y, u.xy);
    emission.flux *= spotEffect(light, -emission.direction);
  } else {
    emission.direction = giSphereDirection(u.xy);
  }
  return emission;
}

// Point and spot lights: the path's power was spread as if it fell off with the inverse square of
// the distance; this makes it fall off as the direct lighting's attenuation does (range included).
float giFirstHitWeight(uint index, float distance) {
  GiSource source = giSources[index];
  if (source.info.x != GI_SOURCE_LIGHT) return 1.0;
  Light light = giLights[source.info.y];
  if (giLightType(light) == LIGHT_DIRECTIONAL) return 1.0;
  return distanceAttenuation(light, distance) * distance * distance;
}

#endif
