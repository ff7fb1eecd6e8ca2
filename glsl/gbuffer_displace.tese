#version 450 core
// G-buffer (and forward) pass, tessellation evaluation for displacement mapping: each generated
// vertex is interpolated over its patch and moved along the interpolated vertex normal by
// uHeightScale x the height map (R, 1 = the top: world units). basePosition keeps the point
// before the move: the fragment stage derives the displaced surface's normal from the same height
// map over it (include/material_sampling.glsl). Shadow rays and VPLs see the undisplaced mesh.

#include "include/gbuffer_vertex.glsl"
#include "include/material_slots.glsl"

layout(triangles, fractional_odd_spacing, ccw) in;

uniform mat4 uViewProjection;
uniform float uHeightScale;
layout(binding = SLOT_HEIGHT) uniform sampler2D uHeightTexture;

in VertexData { GBUFFER_VERTEX_MEMBERS } vin[];
out VertexData { GBUFFER_VERTEX_MEMBERS } vout;

#define INTERPOLATE(member) \
  (gl_TessCoord.x * vin[0].member + gl_TessCoord.y * vin[1].member + gl_TessCoord.z * vin[2].member)

void main() {
  vout.basePosition = INTERPOLATE(worldPosition);
  vout.normal = INTERPOLATE(normal);
  vout.tangent = INTERPOLATE(tangent);
  vout.uv0 = INTERPOLATE(uv0);
  vout.uv1 = INTERPOLATE(uv1);
  vout.color = INTERPOLATE(color);
  vout.sprite = vec2(0.0);
  vout.diffuseLight = INTERPOLATE(diffuseLight);
  vout.specularLight = INTERPOLATE(specularLight);
  float height = 0.0;
  if (hasTexture(SLOT_HEIGHT)) {
    height = textureLod(uHeightTexture, slotUv(SLOT_HEIGHT, vout.uv0, vout.uv1), 0.0).r;
  }
  vec3 n = normalize(vout.normal);
  if (any(isnan(n))) n = vec3(0.0);
  vout.worldPosition = vout.basePosition + n * (uHeightScale * height);
  gl_Position = uViewProjection * vec4(vout.worldPosition, 1.0);
}
