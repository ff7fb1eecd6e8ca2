#version 450 core
// G-buffer (and forward) pass, vertex stage. Inputs: mesh vertices (see
// renderer/src/scene/gpu_scene.cpp for the attribute locations), the draw's world matrix and
// the camera's view-projection. Lines and points go on to gbuffer_lines.geom /
// gbuffer_points.geom, which widen them on screen; displaced triangles to gbuffer_displace.tesc.
// LGH_GOURAUD: the classic models' per-vertex lighting (the lecture's Gouraud shading): every
// analytic light's diffuse and specular terms at the vertex, interpolated by the rasterizer.

#include "include/gbuffer_vertex.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec4 inColor;

// Per draw: instanced attributes that the draw's base instance selects from the scene's draw
// transforms (GpuScene::kDrawTransformLocation).
layout(location = 6) in mat4 inWorld;
layout(location = 10) in mat3 inNormalMatrix;
uniform mat4 uViewProjection;

out VertexData { GBUFFER_VERTEX_MEMBERS } vout;

#ifdef LGH_GOURAUD
#define LGH_LIGHTS_BUFFER
#include "include/light_terms.glsl"

uniform vec3 uCameraPosition;
uniform int uLightCount;
uniform uint uModel;
uniform vec3 uSpecularColor;  // Cook-Torrance: F0
uniform float uExponent;

void lightVertex(vec3 position, vec3 normal) {
  vec3 n = normalize(normal);
  if (any(isnan(n))) n = vec3(0.0, 1.0, 0.0);
  vec3 toViewer = normalize(uCameraPosition - position);
  if (dot(n, toViewer) < 0.0) n = -n;  // the side the camera sees, as the fragment stage does
  SurfacePoint s = defaultSurface(position, n, vec3(1.0), 0.0, 1.0, 1.0);
  s.model = uModel;
  s.specularColor = uSpecularColor;
  s.exponent = uExponent;
  VertexLighting sums = vertexLighting(s, toViewer, uLightCount);
  vout.diffuseLight = sums.diffuse;
  vout.specularLight = sums.specular;
}
#endif

void main() {
  vec4 world = inWorld * vec4(inPosition, 1.0);
  vout.worldPosition = world.xyz;
  vout.basePosition = world.xyz;
  vout.normal = inNormalMatrix * inNormal;
  vout.tangent = vec4(mat3(inWorld) * inTangent.xyz, inTangent.w);
  vout.uv0 = inUv0;
  vout.uv1 = inUv1;
  vout.color = inColor;
  vout.sprite = vec2(0.0);
  vout.diffuseLight = vec3(0.0);
  vout.specularLight = vec3(0.0);
#ifdef LGH_GOURAUD
  lightVertex(world.xyz, vout.normal);
#endif
  gl_Position = uViewProjection * world;
}
