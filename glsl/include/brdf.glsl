// The BRDF library every lighting pass evaluates (direct lighting, the forward pass of blended
// surfaces, per-vertex and per-primitive lighting, the LGH paths, the brute-force reference):
// evaluateBrdfLobes() switches on the surface's material model (include/material_models.glsl).
//  - metallic-roughness, glTF's model: GGX / Trowbridge-Reitz distribution, height-correlated
//    Smith visibility, Schlick Fresnel, Lambert diffuse, with the KHR_materials_* layers of
//    docs/MATERIALS.md: specular/ior (the dielectric Fresnel), sheen (Charlie distribution,
//    Neubelt visibility), clearcoat (a GGX coat over the base) and transmission (approximated as
//    diffuse transmission: light from behind the surface).
//  - the lecture's models (lecture 3, "Local illumination models"): Phong, Blinn-Phong,
//    Oren-Nayar and Cook-Torrance, term for term. Lights here are radiometric (an irradiance
//    scale per light) and the lobes are radiance per unit irradiance, so the lecture's
//    "max(L.N,0) * diffuse" carries Lambert's 1/pi: a diffuse colour c then looks as bright as a
//    glTF base colour c under the same light. Phong's and Blinn-Phong's specular lobes take the
//    same 1/pi and keep the lecture's peak of 1 at every shininess (not energy-normalised, as in
//    the lecture). Cook-Torrance's roughness term is the lecture's R divided by pi and its
//    i_spec = F R G / ((N.V)(N.L)) takes the microfacet 1/4: the normalised form in which it
//    conserves energy (the white-furnace test in tests/integration/test_brdf_models.cpp).
// A pass may define LGH_BRDF_MODELS (MATERIAL_MODEL_BIT_* of the models present) and
// LGH_BRDF_LAYERS (MATERIAL_LAYER_BIT_* of the metallic-roughness layers present) to compile only
// the code of what its frame's G-buffer holds (passes/brdf_features.hpp computes both from the
// frame's materials; docs/LIGHTING.md, "Specialised BRDF"). Without them: every model and layer.
#ifndef LGH_BRDF_GLSL
#define LGH_BRDF_GLSL

#include "include/common.glsl"
#include "include/material_models.glsl"

#ifndef LGH_BRDF_MODELS
#define LGH_BRDF_MODELS 0x7fffffff
#endif
#ifndef LGH_BRDF_LAYERS
#define LGH_BRDF_LAYERS 0x7fffffff
#endif
#define LGH_BRDF_HAS_MODEL(bits) ((LGH_BRDF_MODELS & (bits)) != 0)
#define LGH_BRDF_HAS_LAYER(bits) ((LGH_BRDF_LAYERS & (bits)) != 0)

struct SurfacePoint {
  vec3 position;
  vec3 normal;      // unit, facing the viewer
  vec3 baseColor;   // linear
  float metallic;
  float roughness;  // perceptual
  float occlusion;
  uint model;   // MATERIAL_MODEL_*
  uint layers;  // MATERIAL_LAYER_* bits; the fields below hold their defaults where unset
  vec3 dielectricF0;     // 0.04: IOR 1.5
  float specularWeight;  // KHR_materials_specular's specular (the dielectric F90)
  float clearcoat;
  float clearcoatRoughness;
  vec3 clearcoatNormal;  // unit, facing the viewer
  vec3 sheenColor;
  float sheenRoughness;
  float transmission;
  vec3 transmissionTint;  // KHR_materials_volume's attenuation over the thickness
  // The classic models (MATERIAL_MODEL_PHONG and up); baseColor is their diffuse colour.
  vec3 ambientColor;   // ambient_material
  vec3 specularColor;  // Phong, Blinn-Phong: specular_material; Cook-Torrance: F0
  float exponent;      // Phong, Blinn-Phong: shininess; Oren-Nayar: sigma; Cook-Torrance: m
  // Gouraud and flat shading: the analytic lights' diffuse and specular terms evaluated per
  // vertex or per primitive (unshadowed), which replace the per-pixel sum (direct lighting).
  bool hasVertexLit;
  vec3 vertexLit;
  // Relief mapping's self-shadowing: bit i set = the height field hides analytic light i.
  uint selfShadowMask;
};

// A surface with the defaults of every layer (plain metallic-roughness).
SurfacePoint defaultSurface(vec3 position, vec3 normal, vec3 baseColor, float metallic,
                            float roughness, float occlusion) {
  return SurfacePoint(position, normal, baseColor, metallic, roughness, occlusion,
                      MATERIAL_MODEL_METALLIC_ROUGHNESS, 0u, vec3(0.04), 1.0, 0.0, 0.0, normal,
                      vec3(0.0), 0.0, 0.0, vec3(1.0), baseColor, vec3(0.0), 1.0, false, vec3(0.0),
                      0u);
}

float distributionGgx(float NdotH, float alphaRoughness) {
  float a2 = alphaRoughness * alphaRoughness;
  float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

float visibilitySmithGgxCorrelated(float NdotL, float NdotV, float alphaRoughness) {
  float a2 = alphaRoughness * alphaRoughness;
  float ggxV = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
  float ggxL = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
  float sum = ggxV + ggxL;
  return sum > 0.0 ? 0.5 / sum : 0.0;
}

vec3 fresnelSchlick(vec3 f0, float VdotH) {
  return f0 + (vec3(1.0) - f0) * pow(1.0 - saturate(VdotH), 5.0);
}

// Charlie sheen distribution (Estevez & Kulla 2017), as KHR_materials_sheen specifies.
float distributionCharlie(float NdotH, float sheenRoughness) {
  float alpha = max(sheenRoughness * sheenRoughness, 1e-3);
  float invAlpha = 1.0 / alpha;
  float sin2 = max(1.0 - NdotH * NdotH, 0.0);
  return (2.0 + invAlpha) * pow(sin2, invAlpha * 0.5) / (2.0 * PI);
}

// Neubelt & Pettineo's visibility for sheen: cheap, and bounded at grazing angles.
float visibilityNeubelt(float NdotL, float NdotV) {
  return saturate(1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV)));
}

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Reflected radiance per unit incident irradiance, split into the lobe a light's diffuse colour
// scales and the one its specular colour scales (the lecture's per-light diffuse and specular);
// both already include the cosine factor where the model has one.
struct BrdfLobes {
  vec3 diffuse;
  vec3 specular;
};

BrdfLobes noLobes() { return BrdfLobes(vec3(0.0), vec3(0.0)); }

// glTF metallic-roughness with its layers. For a surface without layers the sum of the lobes is
// exactly the plain glTF BRDF (dielectricF0 = 0.04, specularWeight = 1).
BrdfLobes metallicRoughnessLobes(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  float NdotL = dot(s.normal, toLight);
  vec3 transmitted = vec3(0.0);
#if LGH_BRDF_HAS_LAYER(MATERIAL_LAYER_BIT_TRANSMISSION)
  if ((s.layers & MATERIAL_LAYER_TRANSMISSION) != 0u && NdotL < 0.0) {
    // Light from behind a transmissive surface: the transmitted share of the diffuse lobe.
    transmitted = s.transmission * (1.0 - s.metallic) * s.baseColor * s.transmissionTint *
                  INV_PI * -NdotL;
  }
#endif
  if (NdotL <= 0.0) return BrdfLobes(transmitted, vec3(0.0));
  float NdotV = max(dot(s.normal, toViewer), 1e-4);
  vec3 H = normalize(toLight + toViewer);
  float NdotH = saturate(dot(s.normal, H));
  float VdotH = saturate(dot(toViewer, H));
  float alphaRoughness = max(s.roughness * s.roughness, 1e-3);
  vec3 f0 = mix(s.dielectricF0, s.baseColor, s.metallic);
  vec3 F = fresnelSchlick(f0, VdotH) * mix(s.specularWeight, 1.0, s.metallic);
  float diffuseShare = (1.0 - s.metallic) * (1.0 - s.transmission);
  BrdfLobes lobes;
  lobes.diffuse = (vec3(1.0) - F) * diffuseShare * s.baseColor * INV_PI * NdotL;
  lobes.specular = F * distributionGgx(NdotH, alphaRoughness) *
                   visibilitySmithGgxCorrelated(NdotL, NdotV, alphaRoughness) * NdotL;
#if LGH_BRDF_HAS_LAYER(MATERIAL_LAYER_BIT_SHEEN)
  if ((s.layers & MATERIAL_LAYER_SHEEN) != 0u) {
    // Energy the sheen takes from the base: its directional albedo, approximated by a constant
    // fraction of the sheen colour (docs/MATERIALS.md).
    vec3 sheen = s.sheenColor * distributionCharlie(NdotH, s.sheenRoughness) *
                 visibilityNeubelt(NdotL, NdotV);
    float kept = 1.0 - 0.157 * maxComponent(s.sheenColor);
    lobes.diffuse *= kept;
    lobes.specular = lobes.specular * kept + sheen * NdotL;
  }
#endif
#if LGH_BRDF_HAS_LAYER(MATERIAL_LAYER_BIT_CLEARCOAT)
  if ((s.layers & MATERIAL_LAYER_CLEARCOAT) != 0u) {
    float ccNdotL = dot(s.clearcoatNormal, toLight);
    float ccNdotV = max(dot(s.clearcoatNormal, toViewer), 1e-4);
    float ccNdotH = saturate(dot(s.clearcoatNormal, H));
    float ccAlpha = max(s.clearcoatRoughness * s.clearcoatRoughness, 1e-3);
    float Fc = fresnelSchlick(vec3(0.04), VdotH).x * s.clearcoat;
    float coat = ccNdotL > 0.0 ? Fc * distributionGgx(ccNdotH, ccAlpha) *
                                     visibilitySmithGgxCorrelated(ccNdotL, ccNdotV, ccAlpha) *
                                     ccNdotL
                               : 0.0;
    lobes.diffuse *= 1.0 - Fc;
    lobes.specular = lobes.specular * (1.0 - Fc) + vec3(coat);
  }
#endif
  lobes.diffuse += transmitted;
  return lobes;
}

// Phong and Blinn-Phong, the lecture's
//   max(L.N,0) * diffuse + max(R.V,0)^shininess * specular,   R = -L + 2 (L.N) N
// with Blinn's half vector H = (L + V) / |L + V| and (N.H)^shininess for the second. As in
// OpenGL's lighting, a light below the surface (L.N <= 0) adds no specular either.
BrdfLobes phongLobes(SurfacePoint s, vec3 toViewer, vec3 toLight, bool blinn) {
  float NdotL = dot(s.normal, toLight);
  if (NdotL <= 0.0) return noLobes();
  float c;
  if (blinn) {
    c = max(dot(s.normal, normalize(toLight + toViewer)), 0.0);
  } else {
    vec3 R = -toLight + 2.0 * NdotL * s.normal;
    c = max(dot(R, toViewer), 0.0);
  }
  float highlight = c > 0.0 ? pow(c, s.exponent) : (s.exponent <= 0.0 ? 1.0 : 0.0);
  return BrdfLobes(s.baseColor * INV_PI * NdotL, s.specularColor * INV_PI * highlight);
}

// Oren-Nayar, the lecture's
//   L_r = rho/pi cos(theta_i) (A + B max(0, cos(phi_i - phi_r)) sin(alpha) tan(beta)) L_i,
//   A = 1 - 0.5 sigma^2 / (sigma^2 + 0.33),  B = 0.45 sigma^2 / (sigma^2 + 0.09),
//   alpha = max(theta_i, theta_r),  beta = min(theta_i, theta_r).
// sigma = 0 gives A = 1, B = 0: Lambert.
float orenNayarFactor(vec3 n, vec3 toViewer, vec3 toLight, float sigma) {
  float sigma2 = sigma * sigma;
  float A = 1.0 - 0.5 * sigma2 / (sigma2 + 0.33);
  float B = 0.45 * sigma2 / (sigma2 + 0.09);
  float cosI = saturate(dot(n, toLight));
  float cosR = saturate(dot(n, toViewer));
  // cos(phi_i - phi_r): the angle between L and V projected into the tangent plane.
  vec3 li = toLight - n * cosI;
  vec3 vr = toViewer - n * cosR;
  float projected = sqrt(dot(li, li) * dot(vr, vr));
  float cosPhi = projected > 1e-8 ? max(dot(li, vr) / projected, 0.0) : 0.0;
  float cosAlpha = min(cosI, cosR);  // alpha: the larger angle
  float cosBeta = max(cosI, cosR);   // beta: the smaller one
  float sinAlpha = sqrt(max(1.0 - cosAlpha * cosAlpha, 0.0));
  float tanBeta = sqrt(max(1.0 - cosBeta * cosBeta, 0.0)) / max(cosBeta, 1e-4);
  return A + B * cosPhi * sinAlpha * tanBeta;
}

BrdfLobes orenNayarLobes(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  float NdotL = dot(s.normal, toLight);
  if (NdotL <= 0.0) return noLobes();
  float factor = orenNayarFactor(s.normal, toViewer, toLight, s.exponent);
  return BrdfLobes(s.baseColor * INV_PI * NdotL * factor, vec3(0.0));
}

// The lecture's Cook-Torrance roughness term R (Beckmann) divided by pi, so that the microfacet
// normals' projected areas integrate to 1.
float distributionBeckmann(float NdotH, float m) {
  float m2 = max(m * m, 1e-6);
  float c2 = max(NdotH * NdotH, 1e-8);
  return exp((c2 - 1.0) / (m2 * c2)) / (PI * m2 * c2 * c2);
}

// The lecture's geometric term G = min(1, 2(H.N)(V.N)/(V.H), 2(H.N)(L.N)/(V.H)).
float geometricCookTorrance(float NdotH, float NdotV, float NdotL, float VdotH) {
  float scale = 2.0 * NdotH / max(VdotH, 1e-6);
  return min(1.0, min(scale * NdotV, scale * NdotL));
}

// Cook-Torrance: F R G / (4 (N.V)(N.L)) times N.L, with the lecture's Schlick
// F = F0 + (1 - H.V)^5 (1 - F0). The diffuse colour takes what the Fresnel term leaves on the way
// in and on the way out, (1 - F(N.L)) (1 - F(N.V)): reciprocal, and with it the sum of the lobes
// reflects at most all the light at every angle (weighting by (1 - F(H.V)) alone, as glTF does,
// gains up to 23% at grazing views: tests/integration/test_brdf_models.cpp).
BrdfLobes cookTorranceLobes(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  float NdotL = dot(s.normal, toLight);
  if (NdotL <= 0.0) return noLobes();
  float NdotV = max(dot(s.normal, toViewer), 1e-4);
  vec3 H = normalize(toLight + toViewer);
  float NdotH = saturate(dot(s.normal, H));
  float VdotH = saturate(dot(toViewer, H));
  vec3 F = fresnelSchlick(s.specularColor, VdotH);
  float D = distributionBeckmann(NdotH, s.exponent);
  float G = geometricCookTorrance(NdotH, NdotV, NdotL, VdotH);
  vec3 enters = vec3(1.0) - fresnelSchlick(s.specularColor, NdotL);
  vec3 leaves = vec3(1.0) - fresnelSchlick(s.specularColor, NdotV);
  return BrdfLobes(enters * leaves * s.baseColor * INV_PI * NdotL, F * (D * G / (4.0 * NdotV)));
}

// Reflected radiance per unit incident irradiance for the surface's material model, per lobe.
// Unlit surfaces reflect nothing: their colour is emitted (the G-buffer pass writes it to the
// emissive target). Models left out of LGH_BRDF_MODELS have no case: the frame has none of them.
BrdfLobes evaluateBrdfLobes(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  switch (s.model) {
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BIT_UNLIT)
    case MATERIAL_MODEL_UNLIT:
      return noLobes();
#endif
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BIT_PHONG)
    case MATERIAL_MODEL_PHONG:
      return phongLobes(s, toViewer, toLight, false);
#endif
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BIT_BLINN_PHONG)
    case MATERIAL_MODEL_BLINN_PHONG:
      return phongLobes(s, toViewer, toLight, true);
#endif
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BIT_OREN_NAYAR)
    case MATERIAL_MODEL_OREN_NAYAR:
      return orenNayarLobes(s, toViewer, toLight);
#endif
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BIT_COOK_TORRANCE)
    case MATERIAL_MODEL_COOK_TORRANCE:
      return cookTorranceLobes(s, toViewer, toLight);
#endif
    default:
#if LGH_BRDF_HAS_MODEL(MATERIAL_MODEL_BIT_METALLIC_ROUGHNESS)
      return metallicRoughnessLobes(s, toViewer, toLight);
#else
      return noLobes();
#endif
  }
}

// BRDF(l, v) * max(N.L, 0), both lobes: what a light of one colour (a VPL, a grid light) reflects.
vec3 evaluateBrdfCosine(SurfacePoint s, vec3 toViewer, vec3 toLight) {
  BrdfLobes lobes = evaluateBrdfLobes(s, toViewer, toLight);
  return lobes.diffuse + lobes.specular;
}

// What ambient light (the global term and each light's ambient colour) lights: glTF's diffuse
// colour with its occlusion, the classic models' ambient colour with it, none for unlit.
vec3 ambientResponse(SurfacePoint s) {
  if (s.model == MATERIAL_MODEL_UNLIT) return vec3(0.0);
  vec3 ambient = isClassicModel(s.model) ? s.ambientColor : s.baseColor;
  return ambient * s.occlusion;
}

#endif
