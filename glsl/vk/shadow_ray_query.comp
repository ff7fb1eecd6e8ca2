#version 460
// Shadow rays by ray query: one invocation per pixel, 8 x 8 pixels per work group.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require

#include "include/shadow_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#include "include/balanced_tiles.glsl"  // after the work-group size

bool traceShadowRay(ShadowRay ray) {
  rayQueryEXT query;
  rayQueryInitializeEXT(query, scene, kShadowRayFlags, 0xFF, ray.origin, ray.tMin, ray.direction,
                        ray.tMax);
  // Opaque geometry only: nothing for the shader to confirm, so this runs the traversal through.
  while (rayQueryProceedEXT(query)) {
  }
  return rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT;
}

void main() { traceShadowPixel(uvec2(balancedPixel())); }
