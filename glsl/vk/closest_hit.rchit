#version 460
// The closest hit of a ray: what the ray-query path reads from its committed intersection.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require

#include "../include/hit_record.glsl"

layout(location = 0) rayPayloadInEXT HitRecord hitPayload;
hitAttributeEXT vec2 barycentrics;

void main() {
  hitPayload.t = gl_HitTEXT;
  hitPayload.instance = uint(gl_InstanceCustomIndexEXT);
  hitPayload.geometry = uint(gl_GeometryIndexEXT);
  hitPayload.primitive = uint(gl_PrimitiveID);
  hitPayload.barycentrics = barycentrics;
  hitPayload.frontFace = gl_HitKindEXT == gl_HitKindFrontFacingTriangleEXT ? 1u : 0u;
  hitPayload.unused = 0u;
}
