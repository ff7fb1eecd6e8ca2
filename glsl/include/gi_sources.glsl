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

// Vulkan (the light paths, glsl/vk/gi_*.comp): the same names are members of the push-constant
// block of glsl/vk/include/light_path_constants.glsl, included before this file.
#ifndef VULKAN
uniform uint uSourceCount;
uniform vec4 uSceneSphere;  // xyz: centre, w: radius of the scene's bounding sphere
uniform vec3 uSceneMin;     // the scene's bounding box
uniform vec3 uSceneMax;
#endif

// Directional lights shine onto the scene's bounding box: their paths start on the faces of the box
// that face the light (by projected area), moved this far upstream (in sphere radii) so that every
// path starts in the open.
const float GI_SUN_DISTANCE = 2.0;
const float GI_FAR = 1e30;

// A point on the bounding box's faces that face `direction`, uniform over their projection.
vec3 giBoxEntry(vec3 direction, vec3 u) {
  vec3 size = max(uSceneMax - uSceneMin, vec3(1e-6));
  vec3 projected = abs(direction) * vec3(size.y * size.z, size.x * size.z, size.x * size.y);
  float total = projected.x + projected.y + projected.z;
  float pick = u.z * total;
  int axis = pick < projected.x ? 0 : (pick < projected.x + projected.y ? 1 : 2);
  vec3 point = uSceneMin + size * vec3(u.x, u.y, 0.0);
  if (axis == 0) point = uSceneMin + size * vec3(0.0, u.x, u.y);
  if (axis == 1) point = uSceneMin + size * vec3(u.x, 0.0, u.y);
  // The face whose outward normal points against the light.
  if (direction[axis] < 0.0) point[axis] = uSceneMax[axis];
  return point;
}

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
    emission.origin = giBoxEntry(direction, vec3(u.xy, v.y)) -
                      direction * (GI_SUN_DISTANCE * uSceneSphere.w);
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

// ---- next-event estimation (the path-traced reference) ------------------------------------------

struct GiLightSample {
  vec3 direction;  // unit, from the receiver to the sample
  float distance;  // to the sample; GI_FAR for a light at infinity
  vec3 incident;   // what multiplies BRDF x cos at the receiver, over the sample's probability
  bool area;       // from an emissive triangle
};

// One sample of the light arriving at `x`: a source picked by power (`pick`), a point on it
// (`u`), its light as the direct lighting's diffuse lobe computes it (analytic lights: the
// light's diffuse colour x include/lights.glsl's lightFalloff) or as a Lambertian emitter
// (triangles: L cos_y A / d^2).
GiLightSample giSampleLight(vec3 x, float pick, vec2 u) {
  uint index = giPickSource(pick);
  float probability = max(giSourceProbability(index), 1e-30);
  GiSource source = giSources[index];
  GiLightSample light;
  light.area = source.info.x == GI_SOURCE_TRIANGLE;
  if (light.area) {
    vec2 b = giTriangleBarycentrics(u);
    vec3 y = source.vertex0.xyz + b.x * source.edge1.xyz + b.y * source.edge2.xyz;
    vec3 toY = y - x;
    float d2 = max(dot(toY, toY), 1e-30);
    light.distance = sqrt(d2);
    light.direction = toY / light.distance;
    float cosY = dot(source.normal.xyz, -light.direction);
    if (source.info.z != 0) cosY = abs(cosY);
    light.incident = cosY > 0.0 ? source.radiance.rgb * (cosY * source.vertex0.w / (d2 * probability))
                                : vec3(0.0);
    return light;
  }
  Light analytic = giLights[source.info.y];
  vec3 toLight;
  light.incident = analytic.diffuse.rgb * lightFalloff(analytic, x, toLight) / probability;
  light.direction = toLight;
  light.distance = giLightType(analytic) == LIGHT_DIRECTIONAL
                       ? GI_FAR
                       : length(analytic.positionType.xyz - x);
  return light;
}

#endif
