#version 450 core
// Forward pass of blended surfaces (glTF alphaMode BLEND), drawn after the deferred frame, back to
// front, over the composite: the same material sampling as the G-buffer pass
// (include/material_sampling.glsl) and the same lights and BRDF as the direct lighting pass
// (include/light_terms.glsl), output with the material's alpha for "over" blending. Blended
// surfaces are not in the G-buffer, so no shadow rays start from them (their lights are
// unshadowed) and the LGH's indirect light does not reach them (docs/MATERIALS.md).

#include "include/gbuffer_vertex.glsl"
#include "include/material_sampling.glsl"
#include "include/light_terms.glsl"

in VertexData { GBUFFER_VERTEX_MEMBERS } vin;

uniform float uAmbient;

layout(location = 0) out vec4 outColor;

void main() {
  FragmentInputs inputs = FragmentInputs(vin.worldPosition, vin.basePosition, vin.normal,
                                         vin.tangent, vin.uv0, vin.uv1, vin.color,
                                         vin.diffuseLight, vin.specularLight);
  Derivatives derivatives = screenDerivatives(inputs);
  MaterialSample m = sampleMaterial(inputs, derivatives);
  if (m.discarded) discard;
  SurfacePoint s = m.surface;
  vec3 toViewer = normalize(uCameraPosition - s.position);
  vec3 radiance = m.emissive + uAmbient * ambientResponse(s);
  vec3 direct = vec3(0.0);
  for (int i = 0; i < uLightCount; ++i) {
    LightTerms terms = lightTerms(lights[i], s, toViewer);
    radiance += terms.ambient;
    bool hidden = i < 23 && (s.selfShadowMask & (1u << uint(i))) != 0u;
    if (!hidden) direct += terms.direct;
  }
  radiance += s.hasVertexLit ? s.vertexLit : direct;
  outColor = vec4(radiance, saturate(m.alpha));
}
