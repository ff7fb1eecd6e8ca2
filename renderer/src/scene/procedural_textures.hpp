// Textures made in code, for the demo scene and the tests' small scenes (no files): a checker, a
// brick height map, the normal map of a height map, and a soft light map.
#pragma once

#include <cstdint>

#include "lgh/image.hpp"

namespace lgh {

// size x size RGBA8, tiles x tiles squares alternating between two grey levels (0..255).
Image8 makeCheckerImage(int size, int tiles, std::uint8_t light, std::uint8_t dark);

// Bricks in running bond, `rows` courses: mortar at height 0, brick faces at 1 with bevelled
// edges, a little noise on the faces. R = G = B = height, A = 255.
Image8 makeBrickHeightImage(int size, int rows);

// The colour of the same bricks: red-brown faces varying per brick, light grey mortar (sRGB).
Image8 makeBrickColorImage(int size, int rows);

// An alpha map: rounded holes (alpha 0) in a grid of `cells` x `cells`, soft-edged, white RGB.
Image8 makeHoleAlphaImage(int size, int cells);

// The tangent-space normal map of a height map (R), by central differences, wrapping around:
// `strength` scales the slopes. glTF's convention: +Y (green) points up the image.
Image8 makeNormalMapImage(const Image8& height, float strength);

// A light map: bright in the middle, falling off towards the edges, a shadow band across it.
Image8 makeLightMapImage(int size);

}  // namespace lgh
