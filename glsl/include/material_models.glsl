// Material models and layers: the numbers the G-buffer carries (include/gbuffer.glsl) and
// evaluateBrdfCosine() switches on (include/brdf.glsl). C++ keeps the same numbers in
// lgh::MaterialModel (renderer/src/scene/scene.hpp). A new model takes the next free number here
// and there, a case in evaluateBrdfCosine() and, when it needs parameters of its own, the spare
// bytes of the extension target documented in gbuffer.glsl.
#ifndef LGH_MATERIAL_MODELS_GLSL
#define LGH_MATERIAL_MODELS_GLSL

#define MATERIAL_MODEL_METALLIC_ROUGHNESS 0u  // glTF PBR, with the layers below
#define MATERIAL_MODEL_UNLIT 1u               // KHR_materials_unlit; lines/points without normals

// Layers on top of metallic-roughness (bits of the material target's alpha byte). Without any,
// the extension target is not read at all.
#define MATERIAL_LAYER_CLEARCOAT 1u     // KHR_materials_clearcoat
#define MATERIAL_LAYER_SHEEN 2u         // KHR_materials_sheen
#define MATERIAL_LAYER_SPECULAR 4u      // KHR_materials_specular / KHR_materials_ior
#define MATERIAL_LAYER_TRANSMISSION 8u  // KHR_materials_transmission / KHR_materials_volume

#endif
