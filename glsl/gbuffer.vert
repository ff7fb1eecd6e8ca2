#version 450 core
// G-buffer pass, vertex stage. Inputs: mesh vertices (see renderer/src/scene/gpu_scene.cpp for
// the attribute locations), the instance's world matrix and the camera's view-projection. Lines
// and points go on to gbuffer_lines.geom / gbuffer_points.geom, which widen them on screen.

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec4 inColor;

uniform mat4 uWorld;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;

out VertexData {
  vec3 worldPosition;
  vec3 normal;
  vec4 tangent;
  vec2 uv0;
  vec2 uv1;
  vec4 color;
  vec2 sprite;  // position inside a point's square, [-1, 1]^2; 0 for triangles and lines
} vout;

void main() {
  vec4 world = uWorld * vec4(inPosition, 1.0);
  vout.worldPosition = world.xyz;
  vout.normal = uNormalMatrix * inNormal;
  vout.tangent = vec4(mat3(uWorld) * inTangent.xyz, inTangent.w);
  vout.uv0 = inUv0;
  vout.uv1 = inUv1;
  vout.color = inColor;
  vout.sprite = vec2(0.0);
  gl_Position = uViewProjection * world;
}
