#version 450 core
// G-buffer pass, geometry stage for POINTS: each point becomes a screen-aligned square
// uPointSize pixels across; gbuffer.frag cuts it to a disk when asked (the sprite coordinate).

#include "include/gbuffer_vertex.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 uViewportSize;  // pixels
uniform float uPointSize;    // pixels

in VertexData { GBUFFER_VERTEX_MEMBERS } vin[];
out VertexData { GBUFFER_VERTEX_MEMBERS } vout;

void main() {
  vec4 clip = gl_in[0].gl_Position;
  if (clip.w <= 0.0) return;
  vec2 halfSize = uPointSize / uViewportSize;  // half the size in NDC (NDC spans 2)
  const vec2 corners[4] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));
  for (int k = 0; k < 4; ++k) {
    GBUFFER_COPY_VERTEX(vout, vin[0])
    vout.sprite = corners[k];
    gl_Position = clip + vec4(corners[k] * halfSize * clip.w, 0.0, 0.0);
    EmitVertex();
  }
  EndPrimitive();
}
