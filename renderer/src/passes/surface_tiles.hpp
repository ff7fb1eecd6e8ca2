// The work-group tiles of a frame that can show a surface, found on the CPU before anything is
// drawn: the screen rectangle of the scene's bounding box. On a CPU rasteriser a per-pixel
// compute pass whose output was cleared beforehand dispatches these tiles alone, since a work
// group of background pixels costs there what its shader's first reads and vote cost, while it
// stores nothing (docs/BENCHMARKS.md).
#pragma once

#include <glm/glm.hpp>

#include "gl/gl_objects.hpp"

namespace lgh {

struct Bounds;

// Work groups of LGH_GROUP_2D x LGH_GROUP_2D pixels, in the G-buffer's rows (bottom first):
// `count` of them from tile `first` on. Empty when count.x or count.y is 0.
struct FrameTiles {
  glm::ivec2 first{0};
  glm::ivec2 count{0};
  bool empty() const { return count.x <= 0 || count.y <= 0; }
};

// Every tile of a width x height frame.
FrameTiles allTiles(int width, int height);

// The tiles that hold every pixel a surface inside `worldBounds` can cover, drawn with
// `viewProjection` into a width x height frame, points and lines reaching `marginPixels` beyond
// their vertices: the bounding box's eight corners projected, widened by the margin and a pixel's
// rounding. Every tile when a corner lies on or behind the camera's plane (the projection of the
// box is no longer the hull of its corners' projections), or the box is not finite. No tile for
// an empty box.
FrameTiles surfaceTiles(const Bounds& worldBounds, const glm::mat4& viewProjection, int width,
                        int height, float marginPixels);

// Dispatches `program` (its balancedPixel() reading uFirstTile: include/balanced_tiles.glsl) over
// `tiles`; nothing when they are empty.
void dispatchTiles(GLuint program, const FrameTiles& tiles);

}  // namespace lgh
