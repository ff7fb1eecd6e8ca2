#version 450 core
// G-buffer (and forward) pass, tessellation control for displacement mapping: each triangle is a
// patch whose edges are cut so that a segment covers about uTessellationPixels on screen (the
// screen-space level of detail), at most uTessellationMaxLevel segments. An edge's level depends
// only on its two end points, so neighbouring patches cut a shared edge alike: no cracks.

#include "include/gbuffer_vertex.glsl"

layout(vertices = 3) out;

uniform mat4 uViewProjection;
uniform vec2 uViewportSize;  // pixels
uniform float uTessellationPixels;
uniform float uTessellationMaxLevel;

in VertexData { GBUFFER_VERTEX_MEMBERS } vin[];
out VertexData { GBUFFER_VERTEX_MEMBERS } vout[];

float edgeLevel(vec3 a, vec3 b) {
  vec4 clipA = uViewProjection * vec4(a, 1.0);
  vec4 clipB = uViewProjection * vec4(b, 1.0);
  // An end behind the camera has no screen length: cut finely, the clipper keeps what shows.
  if (clipA.w <= 1e-6 || clipB.w <= 1e-6) return uTessellationMaxLevel;
  vec2 screenA = clipA.xy / clipA.w * 0.5 * uViewportSize;
  vec2 screenB = clipB.xy / clipB.w * 0.5 * uViewportSize;
  return clamp(distance(screenA, screenB) / uTessellationPixels, 1.0, uTessellationMaxLevel);
}

void main() {
  GBUFFER_COPY_VERTEX(vout[gl_InvocationID], vin[gl_InvocationID])
  gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;
  if (gl_InvocationID == 0) {
    // Outer level i belongs to the edge opposite vertex i.
    gl_TessLevelOuter[0] = edgeLevel(vin[1].worldPosition, vin[2].worldPosition);
    gl_TessLevelOuter[1] = edgeLevel(vin[2].worldPosition, vin[0].worldPosition);
    gl_TessLevelOuter[2] = edgeLevel(vin[0].worldPosition, vin[1].worldPosition);
    gl_TessLevelInner[0] =
        max(gl_TessLevelOuter[0], max(gl_TessLevelOuter[1], gl_TessLevelOuter[2]));
  }
}
