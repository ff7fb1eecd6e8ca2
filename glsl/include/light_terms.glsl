// One analytic light's share of the lecture's illumination equation at a surface point:
//   attenuation x spot effect x [ambient_light x ambient_material
//                                + diffuse_light x diffuse lobe + specular_light x specular lobe]
// split into the ambient part, which shadows never touch (it stands for light scattered by the
// surroundings), and the direct part, which the shadow rays' visibility scales. The lobes are the
// material model's (include/brdf.glsl). The emission and the global ambient term are added once
// per surface by the caller. Used by the direct lighting, the forward pass of blended surfaces,
// per-vertex and per-primitive lighting, and relief mapping's self-shadowing.
#ifndef LGH_LIGHT_TERMS_GLSL
#define LGH_LIGHT_TERMS_GLSL

#include "include/brdf.glsl"
#include "include/lights.glsl"

struct LightTerms {
  vec3 ambient;  // never shadowed
  vec3 direct;   // diffuse + specular, scaled by visibility
};

LightTerms lightTerms(Light light, SurfacePoint s, vec3 toViewer) {
  vec3 toLight;
  float falloff = lightFalloff(light, s.position, toLight);
  LightTerms terms;
  terms.ambient = falloff * light.ambient.rgb * ambientResponse(s);
  if (falloff <= 0.0) {
    terms.direct = vec3(0.0);
    return terms;
  }
  BrdfLobes lobes = evaluateBrdfLobes(s, toViewer, toLight);
  terms.direct = falloff * (light.diffuse.rgb * lobes.diffuse + light.specular.rgb * lobes.specular);
  return terms;
}

// Gouraud and flat shading evaluate the diffuse and specular sums of every light at a vertex or
// at a primitive's centre with unit material colours: the fragment then multiplies them by the
// (textured) diffuse colour and the specular map. Linear in both for Phong, Blinn-Phong and
// Oren-Nayar; Cook-Torrance's Fresnel takes the F0 factor here. Unshadowed (the direct lighting
// pass applies the pixel's shadows to the interpolated sum, see direct_lighting.comp).
#ifdef LGH_LIGHTS_BUFFER
struct VertexLighting {
  vec3 diffuse;
  vec3 specular;
};

VertexLighting vertexLighting(SurfacePoint s, vec3 toViewer, int lightCount) {
  VertexLighting sums = VertexLighting(vec3(0.0), vec3(0.0));
  s.baseColor = vec3(1.0);
  if (s.model != MATERIAL_MODEL_COOK_TORRANCE) s.specularColor = vec3(1.0);
  for (int i = 0; i < lightCount; ++i) {
    vec3 toLight;
    float falloff = lightFalloff(lights[i], s.position, toLight);
    if (falloff <= 0.0) continue;
    BrdfLobes lobes = evaluateBrdfLobes(s, toViewer, toLight);
    sums.diffuse += falloff * lights[i].diffuse.rgb * lobes.diffuse;
    sums.specular += falloff * lights[i].specular.rgb * lobes.specular;
  }
  return sums;
}
#endif

#endif
