#version 450 core
// G-buffer pass, geometry stage for LINES: each segment becomes a screen-aligned quad
// uLineWidth pixels wide (core-profile GL draws no lines wider than 1 pixel reliably), so lines
// have the requested width on every driver. Attributes are those of the segment's ends.

#include "include/gbuffer_vertex.glsl"

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 uViewportSize;  // pixels
uniform float uLineWidth;    // pixels

in VertexData { GBUFFER_VERTEX_MEMBERS } vin[];
out VertexData { GBUFFER_VERTEX_MEMBERS } vout;

void emit(int i, vec2 offsetNdc) {
  GBUFFER_COPY_VERTEX(vout, vin[i])
  vout.sprite = vec2(0.0);
  vec4 clip = gl_in[i].gl_Position;
  gl_Position = clip + vec4(offsetNdc * clip.w, 0.0, 0.0);
  EmitVertex();
}

void main() {
  vec4 a = gl_in[0].gl_Position;
  vec4 b = gl_in[1].gl_Position;
  if (a.w <= 0.0 || b.w <= 0.0) return;  // behind the camera: not clipped here, dropped
  vec2 screenA = a.xy / a.w * 0.5 * uViewportSize;
  vec2 screenB = b.xy / b.w * 0.5 * uViewportSize;
  vec2 along = screenB - screenA;
  along = dot(along, along) > 1e-12 ? normalize(along) : vec2(1.0, 0.0);
  vec2 across = vec2(-along.y, along.x) * uLineWidth / uViewportSize;  // half width in NDC
  emit(0, -across);
  emit(0, across);
  emit(1, -across);
  emit(1, across);
  EndPrimitive();
}
