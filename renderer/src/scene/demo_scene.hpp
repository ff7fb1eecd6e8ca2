// The built-in demo scene, generated in code (no files): a Cornell-box-like room.
//
// Units are metres, +Y up, the camera side is +Z:
//  - room: x in [-1, 1], y in [0, 2], z in [-1, 1]; floor (8x8 checker texture), ceiling and back
//    wall (z = -1) white, left wall (x = -1) red, right wall (x = +1) green, front (z = +1) open.
//    All wall normals face into the room.
//  - tall box 0.6 x 1.2 x 0.6 at (-0.35, 0, -0.3), turned +17 degrees about Y;
//  - short box 0.6 x 0.6 x 0.6 at (0.4, 0, 0.3), turned -18 degrees about Y;
//  - metallic sphere (metallic 1, roughness 0.3), radius 0.25, resting on the short box;
//  - emissive panel 0.5 x 0.5 just below the ceiling, facing down (emission only, not a light:
//    the renderer lights with the punctual lights below);
//  - the lecture's illumination models side by side: six spheres of radius 0.1 on the floor at
//    z = 0.82, x = -0.75 .. 0.75 every 0.3, left to right glTF metallic-roughness (roughness
//    0.35), Phong (shininess 40), Blinn-Phong (shininess 160), Lambert (Oren-Nayar at sigma 0),
//    Oren-Nayar (sigma 0.8) and Cook-Torrance plastic (F0 0.04, m 0.15), all clay-coloured.
// Dielectrics are glTF PBR with roughness 0.8, metallic 0.
//
// Materials, by index (what a request's materials[].match.index names): 0 floor_checker, 1
// white, 2 red, 3 green, 4 metal, 5 ceiling_panel, 6 model_metallic_roughness, 7 model_phong,
// 8 model_blinn_phong, 9 model_lambert, 10 model_oren_nayar, 11 model_cook_torrance.
// Textures (what material parameters name by index): 0 the floor's checker, 1 a brick height map,
// 2 its normal map, 3 a light map, 4 the bricks' colour.
//
// Lights (KHR_lights_punctual units):
//  - point, 3 cd, warm white, at (0, 1.75, 0) just under the panel: about 1 lux at the floor
//    centre (radiance ~0.25 off the 0.8 albedo), several lux on the box tops - a well-lit room at
//    exposure 1 with inverse-square falloff;
//  - spot, 5 cd, at (0.8, 1.8, 0.9) aimed at the tall box, cone 0.25 / 0.45 rad;
//  - directional, 0.3 lux, dim cool fill coming in through the open front.
// One glTF-style camera at (0, 1, 3.5) looking down -Z frames the open front (yfov 0.8 rad).
#pragma once

#include "scene/scene.hpp"

namespace lgh {

Scene makeDemoScene();

}  // namespace lgh
