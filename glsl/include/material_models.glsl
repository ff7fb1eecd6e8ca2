// Material models and layers: the numbers the G-buffer carries (include/gbuffer.glsl) and
// evaluateBrdfLobes() switches on (include/brdf.glsl). C++ keeps the same numbers in
// lgh::MaterialModel (renderer/include/lgh/material_settings.hpp). A new model takes the next free
// number here and there, a case in evaluateBrdfLobes() and, when it needs parameters of its own,
// words of the layers target documented in gbuffer.glsl.
#ifndef LGH_MATERIAL_MODELS_GLSL
#define LGH_MATERIAL_MODELS_GLSL

#define MATERIAL_MODEL_METALLIC_ROUGHNESS 0u  // glTF PBR, with the layers below
#define MATERIAL_MODEL_UNLIT 1u               // KHR_materials_unlit; lines/points without normals
#define MATERIAL_MODEL_PHONG 2u               // the lecture's classic models from here on
#define MATERIAL_MODEL_BLINN_PHONG 3u
#define MATERIAL_MODEL_OREN_NAYAR 4u
#define MATERIAL_MODEL_COOK_TORRANCE 5u

// Phong, Blinn-Phong, Oren-Nayar and Cook-Torrance: ambient and specular colours and one exponent
// in the layers target, and Gouraud or flat shading.
bool isClassicModel(uint model) { return model >= MATERIAL_MODEL_PHONG; }

// Layers on top of metallic-roughness (bits of the material target's alpha byte). Without any,
// the extension target is not read at all.
#define MATERIAL_LAYER_CLEARCOAT 1u     // KHR_materials_clearcoat
#define MATERIAL_LAYER_SHEEN 2u         // KHR_materials_sheen
#define MATERIAL_LAYER_SPECULAR 4u      // KHR_materials_specular / KHR_materials_ior
#define MATERIAL_LAYER_TRANSMISSION 8u  // KHR_materials_transmission / KHR_materials_volume

// The same numbers as bits for #if, which takes no unsigned literals: the masks LGH_BRDF_MODELS
// (1 << MATERIAL_MODEL_*) and LGH_BRDF_LAYERS that specialise include/brdf.glsl.
#define MATERIAL_MODEL_BIT_METALLIC_ROUGHNESS 1
#define MATERIAL_MODEL_BIT_UNLIT 2
#define MATERIAL_MODEL_BIT_PHONG 4
#define MATERIAL_MODEL_BIT_BLINN_PHONG 8
#define MATERIAL_MODEL_BIT_OREN_NAYAR 16
#define MATERIAL_MODEL_BIT_COOK_TORRANCE 32
#define MATERIAL_MODEL_BITS_CLASSIC 60  // Phong, Blinn-Phong, Oren-Nayar, Cook-Torrance
#define MATERIAL_LAYER_BIT_CLEARCOAT 1
#define MATERIAL_LAYER_BIT_SHEEN 2
#define MATERIAL_LAYER_BIT_SPECULAR 4
#define MATERIAL_LAYER_BIT_TRANSMISSION 8

// Classic models use the same byte for their own flags.
#define MATERIAL_CLASSIC_VERTEX_LIT 1u  // the layers target's w holds per-vertex/primitive lighting

#endif
