#version 450 core
// Test kernel (tests/integration/test_brdf_models.cpp): evaluates evaluateBrdfLobes() of
// include/brdf.glsl for a list of surfaces and direction pairs, so that the analytic checks
// (Oren-Nayar at sigma 0 against Lambert, where Phong and Blinn-Phong peak, reciprocity, the
// white furnace) run on the shader's own BRDFs.

#include "include/brdf.glsl"

layout(local_size_x = 64) in;

// One evaluation: the surface frame is N = +Z.
struct ProbeInput {
  vec4 baseColorModel;     // rgb base (diffuse) colour, w model
  vec4 specularExponent;   // rgb specular colour (Cook-Torrance: F0), w exponent
  vec4 metallicRoughness;  // metallic, roughness (metallic-roughness), unused, unused
  vec4 toViewer;           // xyz unit
  vec4 toLight;            // xyz unit
};

layout(std430, binding = 0) readonly buffer Inputs { ProbeInput inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };  // diffuse, specular

uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  ProbeInput p = inputs[i];
  SurfacePoint s = defaultSurface(vec3(0.0), vec3(0.0, 0.0, 1.0), p.baseColorModel.rgb,
                                  p.metallicRoughness.x, p.metallicRoughness.y, 1.0);
  s.model = uint(p.baseColorModel.w + 0.5);
  s.specularColor = p.specularExponent.rgb;
  s.exponent = p.specularExponent.w;
  BrdfLobes lobes = evaluateBrdfLobes(s, p.toViewer.xyz, p.toLight.xyz);
  outputs[2u * i] = vec4(lobes.diffuse, 0.0);
  outputs[2u * i + 1u] = vec4(lobes.specular, 0.0);
}
