// A material's texture slots as every stage of the G-buffer and forward passes sees them: texture
// unit = slot, bit (1 << slot) in uTextureMask / uTexCoord1Mask, and KHR_texture_transform per
// slot. C++ fills them from materialTextureSlots() (renderer/src/scene/scene.hpp), in this order.
#ifndef LGH_MATERIAL_SLOTS_GLSL
#define LGH_MATERIAL_SLOTS_GLSL

#define SLOT_BASE_COLOR 0
#define SLOT_METALLIC_ROUGHNESS 1
#define SLOT_NORMAL 2
#define SLOT_OCCLUSION 3
#define SLOT_EMISSIVE 4
#define SLOT_CLEARCOAT 5
#define SLOT_CLEARCOAT_ROUGHNESS 6
#define SLOT_CLEARCOAT_NORMAL 7
#define SLOT_SHEEN_COLOR 8
#define SLOT_SHEEN_ROUGHNESS 9
#define SLOT_SPECULAR 10        // KHR_materials_specular's A; classic models: the gloss map (R)
#define SLOT_SPECULAR_COLOR 11  // KHR_materials_specular's colour; classic models: specular map
#define SLOT_TRANSMISSION 12
#define SLOT_LIGHT_MAP 13       // precomputed illumination (sRGB)
#define SLOT_HEIGHT 14          // height map (R): bump, parallax, relief, displacement
#define SLOT_COUNT 15

uniform uint uTextureMask;
uniform uint uTexCoord1Mask;              // bit set: that texture reads TEXCOORD_1
uniform mat3x2 uUvTransform[SLOT_COUNT];  // KHR_texture_transform per slot

bool hasTexture(int slot) { return (uTextureMask & (1u << uint(slot))) != 0u; }

bool slotUsesUv1(int slot) { return (uTexCoord1Mask & (1u << uint(slot))) != 0u; }

// A slot's texture coordinate from the two UV sets.
vec2 slotUv(int slot, vec2 uv0, vec2 uv1) {
  return uUvTransform[slot] * vec3(slotUsesUv1(slot) ? uv1 : uv0, 1.0);
}

#endif
