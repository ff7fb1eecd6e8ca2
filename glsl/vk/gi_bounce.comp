#version 460
// Light paths, one bounce: one invocation per path resolves its ray's closest hit into a surface
// point, leaves a VPL there with the path's flux times the diffuse albedo (isotropic over the
// hemisphere the light came from: I = flux x albedo / (2 pi)), and, before the last bounce, sends
// the path on in a cosine-weighted direction with its flux times the albedo. A path that missed,
// died, or met the back of a single-sided surface (absorbed) leaves a dark VPL and no ray.
// docs/GI.md. Recorded by renderer/src/vk/light_path_tracer.cpp after each trace, in the same
// submission.
// Inputs: the closest hits, the paths' state, the scene's triangles and materials, the source
// table. Outputs: the bounce's VPL slot, the next rays, the paths' state.
#extension GL_GOOGLE_include_directive : require

#include "include/light_path_constants.glsl"
#include "include/gi_sources.glsl"
#include "include/hit_surface.glsl"
#include "include/lgh_types.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = LGH_BIND_GI_RAYS) buffer Rays { vec4 rays[]; };
layout(std430, binding = LGH_BIND_GI_HITS) readonly buffer Hits { HitRecord hits[]; };
layout(std430, binding = LGH_BIND_GI_PATHS) buffer Paths { vec4 paths[]; };
layout(std430, binding = LGH_BIND_GI_VPLS) writeonly buffer Vpls { PointLight vpls[]; };

// uSlot: the VPL slot of this bounce: VPL = vpls[uSlot * uPathCount + path].
uint pathIndex() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
}

void writeVpl(uint path, vec3 position, vec3 intensity) {
  PointLight vpl;
  vpl.positionPad = vec4(position, 0.0);
  vpl.intensityPad = vec4(intensity, 0.0);
  vpls[uSlot * uPathCount + path] = vpl;
}

void endPath(uint path) {
  writeVpl(path, vec3(0.0), vec3(0.0));
  paths[path] = vec4(0.0);
  if (uLastBounce == 0u) {
    rays[2u * path] = vec4(0.0);
    rays[2u * path + 1u] = vec4(0.0, 0.0, 1.0, -1.0);  // tMax < tMin: not traced
  }
}

void main() {
  uint path = pathIndex();
  if (path >= uPathCount) return;
  vec4 state = paths[path];
  HitRecord hit = hits[path];
  if (!hitRecordIsHit(hit) || !any(greaterThan(state.rgb, vec3(0.0)))) {
    endPath(path);
    return;
  }
  vec3 direction = rays[2u * path + 1u].xyz;
  HitSurface surface = resolveHit(hit, direction);
  if (surface.backFace) {
    endPath(path);
    return;
  }
  vec3 flux = state.rgb;
  if (uBounce == 1u) flux *= giFirstHitWeight(floatBitsToUint(state.w), hit.t * length(direction));
  vec3 reflected = flux * surface.albedo;
  bool valid = !any(isinf(reflected)) && !any(isnan(reflected)) && !any(isnan(surface.position));
  if (!valid || !any(greaterThan(reflected, vec3(0.0)))) {
    endPath(path);
    return;
  }
  // On the surface itself: an isotropic VPL lifted off its surface lights that surface at grazing
  // angles, and a plane of them lights it with 2 pi sigma I however small the lift (docs/GI.md).
  writeVpl(path, surface.position, reflected / (2.0 * PI));
  vec3 position = surface.position + surface.geometricNormal * uSurfaceOffset;
  if (uLastBounce != 0u) return;
  uint seed = giPathSeed(uSeed, path);
  vec3 next = giCosineDirection(surface.normal, vec2(giRandom(seed, uBounce, 0u),
                                                     giRandom(seed, uBounce, 1u)));
  rays[2u * path] = vec4(position, 0.0);
  rays[2u * path + 1u] = vec4(next, GI_FAR);
  paths[path] = vec4(reflected, state.w);
}
