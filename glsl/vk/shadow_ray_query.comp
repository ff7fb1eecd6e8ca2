#version 460
// Shadow rays by ray query: one invocation per pixel, 8 x 8 pixels per work group, over the
// batch's tiles where it names them (the words of every other pixel were zeroed).
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#include "include/shadow_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// The launch covers the batch's tiles from this one on (vk::RayBatchShape::tiles).
#define LGH_FIRST_TILE uvec2(trace.firstTileX, trace.firstTileY)
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

// A subgroup of pixels without a surface (origin w = 0) writes nothing: their visibility words
// were filled with zeros before the launch (TraceBatch::zeroed). On a CPU device a subgroup is one
// SIMD vector, and a branch on its vote is a real branch (glsl/include/skip_background.glsl).
void main() {
  uvec2 pixel = uvec2(balancedPixel());
  bool inBatch = pixel.x < trace.width && pixel.y < trace.height;
  bool surface = inBatch && origins[pixel.y * trace.width + pixel.x].w > 0.0;
  if (subgroupAny(surface)) traceShadowPixel(pixel);
}
