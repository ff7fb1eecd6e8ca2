// The camera paths of the path-traced reference (renderer/src/gi/path_traced_reference.hpp): one
// per pixel and sample of an iteration, path = pixel * uSamples + sample, advanced a vertex at a
// time between closest-hit batches (the bounce) and occlusion batches (next-event estimation).
#ifndef LGH_GI_CAMERA_PATHS_GLSL
#define LGH_GI_CAMERA_PATHS_GLSL

#include "include/slots.glsl"

struct GiCameraPath {  // 96 bytes
  vec4 position;    // xyz: the current vertex, already off its surface; w: 1 while the path lives
  vec4 normal;      // xyz: its geometric normal, facing where the path came from
  vec4 throughput;  // rgb: the path's weight after this vertex's bounce
  vec4 pending;     // rgb: the next-event contribution awaiting its occlusion ray
  vec4 next;        // xyz: the bounce direction
  vec4 radiance;    // rgb: what the path gathered in this iteration
};

layout(std430, binding = LGH_BIND_GI_PATHS) buffer GiCameraPaths { GiCameraPath cameraPaths[]; };
layout(std430, binding = LGH_BIND_GI_RAYS) buffer Rays { vec4 rays[]; };

uniform uint uPathCount;
uniform uint uSamples;  // paths per pixel in an iteration
uniform uint uSeed;     // the iteration's seed
uniform float uSurfaceOffset;

// Rays to a sampled light end this fraction short of it (the sample lies on a surface).
const float GI_SHADOW_END = 1e-3;

uint cameraPathIndex() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
}

void writeRay(uint path, vec3 origin, vec3 direction, float tMax) {
  rays[2u * path] = vec4(origin, 0.0);
  rays[2u * path + 1u] = vec4(direction, tMax);
}

void writeNoRay(uint path) {
  rays[2u * path] = vec4(0.0);
  rays[2u * path + 1u] = vec4(0.0, 0.0, 1.0, -1.0);  // tMax < tMin: not traced
}

bool finite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// The occlusion ray of a next-event sample, or none for a contribution of 0.
void writeShadowRay(uint path, vec3 origin, vec3 direction, float distance, vec3 contribution) {
  if (any(greaterThan(contribution, vec3(0.0))) && finite(contribution)) {
    writeRay(path, origin, direction, distance * (1.0 - GI_SHADOW_END));
  } else {
    writeNoRay(path);
  }
}

#endif
