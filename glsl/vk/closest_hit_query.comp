#version 460
// Closest hits by ray query: one invocation per ray, 64 per work group, rows of the 2D launch
// (include/hit_rays.glsl) in the work groups' y.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

#include "include/hit_rays.glsl"

layout(local_size_x = 64) in;

HitRecord traceHit(vec3 origin, float tMin, vec3 direction, float tMax) {
  rayQueryEXT query;
  rayQueryInitializeEXT(query, scene, hitRayFlags(), 0xFF, origin, tMin, direction, tMax);
  // Opaque geometry only: the traversal commits every triangle it meets on its own.
  while (rayQueryProceedEXT(query)) {
  }
  if (rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT) {
    return missRecord();
  }
  HitRecord record;
  record.t = rayQueryGetIntersectionTEXT(query, true);
  record.instance = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, true));
  record.geometry = uint(rayQueryGetIntersectionGeometryIndexEXT(query, true));
  record.primitive = uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true));
  record.barycentrics = rayQueryGetIntersectionBarycentricsEXT(query, true);
  record.frontFace = rayQueryGetIntersectionFrontFaceEXT(query, true) ? 1u : 0u;
  record.unused = 0u;
  return record;
}

void main() { traceHitRay(gl_GlobalInvocationID.xy); }
