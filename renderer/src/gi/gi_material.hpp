// A glTF material as the light paths and the path-traced reference read it at a ray hit: the
// CPU half of glsl/include/gi_material.glsl (GiMaterial, std430). The two functions here and there
// are the one place that follows the material model (gbuffer.frag, scene/scene.hpp's Material):
// base colour factor, base-colour texture (as a layer of the downsampled albedo array), metallic
// (0 for the lecture's classic models, whose `diffuse` is the base colour) and roughness factors,
// and emission (factor x the emissive texture's mean colour).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace lgh {

struct GiMaterialGpu {
  glm::vec4 baseColorFactor{1.0F};
  glm::vec4 emission{0.0F};                            // rgb
  glm::vec4 params{0.0F};                              // x: metallic, y: roughness
  glm::ivec4 baseColorTexture{-1, 0, 0x2901, 0x2901};  // layer, texCoord, wrapS, wrapT
};
static_assert(sizeof(GiMaterialGpu) == 64, "GiMaterialGpu must match GiMaterial (std430)");

// `baseColorLayer`: the material's base-colour texture in the albedo array (-1: none, or not
// there); `emissiveTextureMean`: the linear mean of its emissive texture (1 without one).
GiMaterialGpu packGiMaterial(const Material& material, int baseColorLayer,
                             const glm::vec3& emissiveTextureMean);

// The radiance a surface of this material emits (what packGiMaterial stores as emission).
glm::vec3 emittedRadiance(const Material& material, const glm::vec3& emissiveTextureMean);

// Whether the light paths read the two materials alike: the fields above, nothing else (a
// request's `materials` that change only, say, the shading mode keep the hit geometry).
bool sameForLightPaths(const Material& a, const Material& b);

}  // namespace lgh
