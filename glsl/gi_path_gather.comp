#version 450 core
// Path-traced reference, after an occlusion batch: a next-event contribution whose ray got
// through is gathered; then, unless this was the last vertex, the bounce ray goes out.

#include "include/gi_camera_paths.glsl"
#include "include/hit_record.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = LGH_BIND_GI_HITS) readonly buffer Hits { HitRecord hits[]; };

uniform uint uLastVertex;  // 1: no bounce after this vertex

void main() {
  uint path = cameraPathIndex();
  if (path >= uPathCount) return;
  GiCameraPath state = cameraPaths[path];
  if (any(greaterThan(state.pending.rgb, vec3(0.0))) && !hitRecordIsHit(hits[path])) {
    state.radiance.rgb += state.pending.rgb;
  }
  state.pending = vec4(0.0);
  cameraPaths[path] = state;
  bool bounce = uLastVertex == 0u && state.position.w > 0.0;
  if (bounce) {
    writeRay(path, state.position.xyz, state.next.xyz, 1e30);
  } else {
    writeNoRay(path);
  }
}
