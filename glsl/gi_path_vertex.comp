#version 450 core
// Path-traced reference, a vertex after the first: the bounce's closest hit resolved into a
// surface point (a diffuse vertex, as the VPLs' light paths treat every bounce), next-event
// estimation to every light source, and a cosine-weighted bounce with weight albedo.

#include "include/gi_camera_paths.glsl"
#include "include/gi_sources.glsl"
#include "include/hit_surface.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = LGH_BIND_GI_HITS) readonly buffer Hits { HitRecord hits[]; };

uniform uint uVertex;  // 1..bounces

void main() {
  uint path = cameraPathIndex();
  if (path >= uPathCount) return;
  GiCameraPath state = cameraPaths[path];
  HitRecord hit = hits[path];
  if (state.position.w <= 0.0 || !hitRecordIsHit(hit)) {
    state.position.w = 0.0;
    cameraPaths[path] = state;
    writeNoRay(path);
    return;
  }
  HitSurface surface = resolveHit(hit, state.next.xyz);
  if (surface.backFace) {  // absorbed, as the light paths treat it
    state.position.w = 0.0;
    cameraPaths[path] = state;
    writeNoRay(path);
    return;
  }
  vec3 origin = surface.position + surface.geometricNormal * uSurfaceOffset;
  uint seed = giPathSeed(uSeed, path);
  GiLightSample light = giSampleLight(surface.position, giRandom(seed, uVertex, 0u),
                                      vec2(giRandom(seed, uVertex, 1u), giRandom(seed, uVertex, 2u)));
  float cosine = dot(surface.geometricNormal, light.direction) > 0.0
                     ? max(dot(surface.normal, light.direction), 0.0)
                     : 0.0;
  vec3 contribution = state.throughput.rgb * surface.albedo * (INV_PI * cosine) * light.incident;
  if (!finite(contribution)) contribution = vec3(0.0);
  writeShadowRay(path, origin, light.direction, light.distance, contribution);

  vec3 next = giCosineDirection(surface.normal,
                                vec2(giRandom(seed, uVertex, 3u), giRandom(seed, uVertex, 4u)));
  vec3 throughput = dot(next, surface.geometricNormal) > 0.0
                        ? state.throughput.rgb * surface.albedo
                        : vec3(0.0);
  state.position = vec4(origin, any(greaterThan(throughput, vec3(0.0))) ? 1.0 : 0.0);
  state.normal = vec4(surface.geometricNormal, 0.0);
  state.throughput = vec4(throughput, 0.0);
  state.pending = vec4(contribution, 0.0);
  state.next = vec4(next, 0.0);
  cameraPaths[path] = state;
}
