// The shadow rays of one batch (renderer/src/vk/shadow_tracer.hpp), shared by both tracing
// paths so that they give the same bits: the bindings, the push constants, the ray set up from a
// pixel's origin and target, and the loop that packs a pixel's visibility into words. The
// including shader defines traceShadowRay(), the only thing the paths do differently.

layout(set = 0, binding = 0) uniform accelerationStructureEXT scene;
layout(std430, set = 0, binding = 1) readonly buffer Origins { vec4 origins[]; };
layout(std430, set = 0, binding = 2) readonly buffer Targets { vec4 targets[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Visibility { uint visibility[]; };

// TracePushConstants in renderer/src/vk/trace_layout.hpp.
layout(push_constant, std430) uniform TraceConstants {
  uint width;
  uint height;
  uint raysPerPixel;
  uint words;
  float tMin;
  float tMaxInfinite;
  float endEpsilon;
  uint firstTileX;  // the launch's first tile (the ray-query path's tiles; 0 otherwise)
  uint firstTileY;
} trace;

// Every shadow ray is opaque and done at its first hit: any hit means occluded.
const uint kShadowRayFlags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsOpaqueEXT;

struct ShadowRay {
  vec3 origin;
  float tMin;
  vec3 direction;  // unit length
  float tMax;
};

// What becomes of one target.
const uint kNoRay = 0u;    // no ray: its bit stays 0
const uint kTrace = 1u;    // trace it: its bit says whether it got from tMin to tMax unoccluded
const uint kVisible = 2u;  // a point within tMin of the origin: nothing to trace, visible

// `precise` keeps the compiler from fusing this arithmetic differently in the two paths'
// shaders: the same ray comes out of both, to the bit.
uint setUpShadowRay(vec3 origin, vec4 target, out ShadowRay ray) {
  ray.origin = origin;
  ray.tMin = trace.tMin;
  ray.direction = vec3(0.0, 0.0, 1.0);
  ray.tMax = trace.tMin;
  if (!(target.w >= 0.0)) return kNoRay;  // w < 0 (or NaN)
  bool atInfinity = target.w == 0.0;
  precise vec3 towards = atInfinity ? target.xyz : target.xyz - origin;
  precise float len = length(towards);
  if (isnan(len) || isinf(len)) return kNoRay;
  if (len == 0.0) return atInfinity ? kNoRay : kVisible;
  precise vec3 direction = towards / len;
  // A light at infinity is tMaxInfinite away; a point ends endEpsilon (relative) short of it.
  precise float tMax = atInfinity ? trace.tMaxInfinite : len * (1.0 - trace.endEpsilon);
  ray.direction = direction;
  ray.tMax = tMax;
  return tMax > ray.tMin ? kTrace : kVisible;
}

// True when nothing in `scene` blocks `ray`; defined by the including shader.
bool traceShadowRay(ShadowRay ray);

// Writes every word of the pixel at `pixelCoord` (if it is within the batch).
void traceShadowPixel(uvec2 pixelCoord) {
  if (pixelCoord.x >= trace.width || pixelCoord.y >= trace.height) return;
  uint pixel = pixelCoord.y * trace.width + pixelCoord.x;
  vec4 origin = origins[pixel];
  for (uint word = 0u; word < trace.words; ++word) {
    uint bits = 0u;
    uint first = word * 32u;
    uint count = origin.w > 0.0 ? min(32u, trace.raysPerPixel - first) : 0u;
    for (uint bit = 0u; bit < count; ++bit) {
      ShadowRay ray;
      uint what = setUpShadowRay(origin.xyz, targets[pixel * trace.raysPerPixel + first + bit], ray);
      if (what == kVisible || (what == kTrace && traceShadowRay(ray))) bits |= 1u << bit;
    }
    visibility[pixel * trace.words + word] = bits;
  }
}
