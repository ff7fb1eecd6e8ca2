#version 450 core
// G-buffer (and forward) pass, geometry stage of flat shading (the lecture's per-primitive
// shading): each triangle is lit once, at its centre with its face normal, by every analytic
// light, and every fragment of it gets that one result and the face normal.

#define LGH_LIGHTS_BUFFER
#include "include/gbuffer_vertex.glsl"
#include "include/light_terms.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

uniform vec3 uCameraPosition;
uniform int uLightCount;
uniform uint uModel;
uniform vec3 uSpecularColor;  // Cook-Torrance: F0
uniform float uExponent;

in VertexData { GBUFFER_VERTEX_MEMBERS } vin[];
out VertexData { GBUFFER_VERTEX_MEMBERS } vout;

void main() {
  vec3 p0 = vin[0].worldPosition;
  vec3 p1 = vin[1].worldPosition;
  vec3 p2 = vin[2].worldPosition;
  vec3 centre = (p0 + p1 + p2) / 3.0;
  vec3 face = cross(p1 - p0, p2 - p0);
  vec3 averaged = vin[0].normal + vin[1].normal + vin[2].normal;
  face = dot(face, face) > 1e-24 ? normalize(face) : normalize(averaged);
  if (dot(face, averaged) < 0.0) face = -face;  // the winding may disagree with the normals
  vec3 toViewer = normalize(uCameraPosition - centre);
  vec3 lit = dot(face, toViewer) < 0.0 ? -face : face;
  SurfacePoint s = defaultSurface(centre, lit, vec3(1.0), 0.0, 1.0, 1.0);
  s.model = uModel;
  s.specularColor = uSpecularColor;
  s.exponent = uExponent;
  VertexLighting sums = vertexLighting(s, toViewer, uLightCount);
  for (int i = 0; i < 3; ++i) {
    GBUFFER_COPY_VERTEX(vout, vin[i])
    vout.normal = face;
    vout.diffuseLight = sums.diffuse;
    vout.specularLight = sums.specular;
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
