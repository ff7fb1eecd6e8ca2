// The closest-hit batches (renderer/src/vk/shadow_tracer.hpp, "Closest hits"), shared by both
// tracing paths so that they write the same records: the bindings, the push constants, the ray
// read from its buffer and the record written back. The including shader defines traceHit(), the
// only thing the paths do differently.

#include "../../include/hit_record.glsl"

layout(set = 0, binding = 0) uniform accelerationStructureEXT scene;
layout(std430, set = 0, binding = 1) readonly buffer Rays { vec4 rays[]; };  // 2 per ray
layout(std430, set = 0, binding = 2) writeonly buffer Hits { HitRecord hits[]; };

// HitPushConstants in renderer/src/vk/trace_layout.hpp.
layout(push_constant, std430) uniform HitConstants {
  uint rayCount;
  uint anyHit;       // 1: occlusion only, done at the first hit found
  uint launchWidth;  // rays per row of the 2D launch
  uint unused;
} batch;

// Opaque geometry; both sides of every triangle (the instances cull no faces).
uint hitRayFlags() {
  return gl_RayFlagsOpaqueEXT | (batch.anyHit != 0u ? gl_RayFlagsTerminateOnFirstHitEXT : 0u);
}

HitRecord missRecord() {
  HitRecord record;
  record.t = -1.0;
  record.instance = 0u;
  record.geometry = 0u;
  record.primitive = 0u;
  record.barycentrics = vec2(0.0);
  record.frontFace = 0u;
  record.unused = 0u;
  return record;
}

// The hit of one ray (missRecord() for none); defined by the including shader.
HitRecord traceHit(vec3 origin, float tMin, vec3 direction, float tMax);

void traceHitRay(uvec2 launch) {
  uint ray = launch.y * batch.launchWidth + launch.x;
  if (launch.x >= batch.launchWidth || ray >= batch.rayCount) return;
  vec4 originMin = rays[2u * ray];
  vec4 directionMax = rays[2u * ray + 1u];
  bool traced = directionMax.w > originMin.w && dot(directionMax.xyz, directionMax.xyz) > 0.0;
  hits[ray] = traced ? traceHit(originMin.xyz, originMin.w, directionMax.xyz, directionMax.w)
                     : missRecord();
}
