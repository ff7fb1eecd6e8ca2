// One closest-hit result of a ray batch (renderer/src/vk/shadow_tracer.hpp, "Closest hits"): 32
// bytes, written by the Vulkan tracer (glsl/vk/include/hit_rays.glsl) and read by the GL passes
// that resolve hits into surface points (glsl/include/hit_surface.glsl). Valid GLSL for both.
#ifndef LGH_HIT_RECORD_GLSL
#define LGH_HIT_RECORD_GLSL

struct HitRecord {
  float t;            // distance along the ray (in units of its direction); < 0: a miss
  uint instance;      // index in Scene::instances
  uint geometry;      // the primitive among its mesh's primitives that have triangles
  uint primitive;     // the triangle among that primitive's kept triangles
  vec2 barycentrics;  // of the triangle's vertices 1 and 2
  uint frontFace;     // 1: the ray met the counter-clockwise side
  uint unused;
};

bool hitRecordIsHit(HitRecord hit) { return hit.t >= 0.0; }

#endif
