#version 450 core
// G-buffer pass, fragment stage: samples the material (include/material_sampling.glsl: textures
// with KHR_texture_transform, multi-texturing, surface detail) and writes the layout documented
// in include/gbuffer.glsl: the material model, and its parameters in the layers target (the
// KHR_materials_* layers of metallic-roughness, or the classic models' words).

#include "include/gbuffer_vertex.glsl"
#include "include/material_sampling.glsl"

in VertexData { GBUFFER_VERTEX_MEMBERS } vin;

#if !LGH_MATERIAL_HAS(LGH_MATERIAL_DISCARD)
// Nothing discards: the depth test may run before the shader, so hidden fragments cost nothing.
layout(early_fragment_tests) in;
#endif

uniform bool uPointDisk;  // points: cut the square to a disk

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outMaterial;
layout(location = 4) out vec4 outEmissive;
layout(location = 5) out uvec4 outLayers;

void main() {
#ifdef LGH_DISPLACED
  vec3 basePosition = vin.basePosition;
#else
  vec3 basePosition = vin.worldPosition;  // the same value: one varying less
#endif
#if LGH_MATERIAL_HAS(LGH_MATERIAL_SURFACE_FRAME)
  FragmentInputs inputs = FragmentInputs(vin.worldPosition, basePosition, vin.normal, vin.tangent,
                                         vin.uv0, vin.uv1, vin.color, vin.diffuseLight,
                                         vin.specularLight);
#else
  // Nothing reads texture coordinates or tangents: left out, they are varyings fewer for a CPU
  // rasteriser to set up per triangle and interpolate (docs/BENCHMARKS.md).
  FragmentInputs inputs = FragmentInputs(vin.worldPosition, basePosition, vin.normal,
                                         vec4(1.0, 0.0, 0.0, 1.0), vec2(0.0), vec2(0.0), vin.color,
                                         vin.diffuseLight, vin.specularLight);
#endif
  Derivatives derivatives = screenDerivatives(inputs);
#if LGH_MATERIAL_HAS(LGH_MATERIAL_DISCARD)
  if (uPointDisk && dot(vin.sprite, vin.sprite) > 1.0) discard;
#endif
  MaterialSample m = sampleMaterial(inputs, derivatives);
#if LGH_MATERIAL_HAS(LGH_MATERIAL_DISCARD)
  if (m.discarded) discard;
#endif
  SurfacePoint s = m.surface;
  outPosition = vec4(vin.worldPosition, 1.0 + float(s.selfShadowMask));
  outNormal = vec4(s.normal, 0.0);
  outAlbedo = vec4(s.baseColor, s.occlusion);
  bool classic = LGH_MATERIAL_HAS(LGH_MATERIAL_CLASSIC) && isClassicModel(s.model);
  outMaterial = vec4(classic ? 0.0 : s.metallic, classic ? 0.0 : s.roughness,
                     float(s.model) / 255.0, float(m.flags) / 255.0);
  outEmissive = vec4(m.emissive, 0.0);
  if (classic) {
    outLayers = encodeClassic(s);
  } else {
    outLayers = s.layers != 0u ? encodeLayers(s) : uvec4(0u);
  }
}
