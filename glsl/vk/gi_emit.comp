#version 460
// Light paths, start: one invocation per path picks a light source by power, the path's first
// ray and flux, and for an emissive triangle its emission VPL (a point on the triangle: the area
// light's direct light reaches the frame through the LGH). docs/GI.md. Recorded by
// renderer/src/vk/light_path_tracer.cpp ahead of the traces and bounces, in one submission.
// Inputs: the source table, the frame's lights. Outputs: the rays (closest-hit batch), the paths'
// state, the emission slot of the VPLs.
#extension GL_GOOGLE_include_directive : require

#include "include/light_path_constants.glsl"
#include "include/gi_sources.glsl"
#include "include/lgh_types.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = LGH_BIND_GI_RAYS) writeonly buffer Rays { vec4 rays[]; };
// Per path: rgb flux, w: the source index (bits), or all 0 for a dead path.
layout(std430, binding = LGH_BIND_GI_PATHS) writeonly buffer Paths { vec4 paths[]; };
layout(std430, binding = LGH_BIND_GI_VPLS) writeonly buffer Vpls { PointLight vpls[]; };

uint pathIndex() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
}

void main() {
  uint path = pathIndex();
  if (path >= uPathCount) return;
  uint seed = giPathSeed(uSeed, path);
  uint source = giPickSource(giRandom(seed, 0u, 0u));
  vec4 u = vec4(giRandom(seed, 0u, 1u), giRandom(seed, 0u, 2u), giRandom(seed, 0u, 3u),
                giRandom(seed, 0u, 4u));
  vec2 v = vec2(giRandom(seed, 0u, 5u), giRandom(seed, 0u, 6u));
  GiEmission emission = giEmit(source, 1.0 / float(uPathCount), u, v);
  vec3 origin = emission.origin;  // the emission VPL lies on the triangle, the ray starts off it
  if (emission.fromTriangle) origin += emission.normal * uSurfaceOffset;
  bool valid = !any(isinf(emission.flux)) && !any(isnan(emission.flux));
  vec3 flux = valid ? max(emission.flux, vec3(0.0)) : vec3(0.0);
  rays[2u * path] = vec4(origin, 0.0);
  rays[2u * path + 1u] = vec4(emission.direction, any(greaterThan(flux, vec3(0.0))) ? emission.tMax : -1.0);
  paths[path] = vec4(flux, uintBitsToFloat(source));
  if (uEmissionSlots == 1u) {
    // A Lambertian emitter's power leaves one hemisphere: isotropic over it, I = flux / (2 pi).
    PointLight vpl;
    vpl.positionPad = vec4(emission.origin, 0.0);
    vpl.intensityPad = vec4(emission.fromTriangle ? flux / (2.0 * PI) : vec3(0.0), 0.0);
    vpls[path] = vpl;
  }
}
