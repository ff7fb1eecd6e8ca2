#include "passes/surface_tiles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gl/slots.hpp"
#include "scene/scene.hpp"

namespace lgh {
namespace {

// Pixels a projected vertex may be off by: the rounding of its position to the pixel grid and the
// rasteriser's snapping, with room to spare.
constexpr float kRoundingPixels = 2.0F;

// The tiles of the pixel span [low, high) along an axis of `pixels` pixels, as (first, count).
glm::ivec2 tileSpan(float low, float high, int pixels) {
  // Clamped as floats first: a far-off corner's value may not fit an int.
  const auto clamped = [pixels](float value) {
    return std::clamp(value, 0.0F, static_cast<float>(pixels));
  };
  const int lowPixel = static_cast<int>(std::floor(clamped(low)));
  const int highPixel = static_cast<int>(std::ceil(clamped(high)));
  if (highPixel <= lowPixel) return glm::ivec2(0);
  const int first = lowPixel / LGH_GROUP_2D;
  const int last = (highPixel - 1) / LGH_GROUP_2D;
  return {first, last - first + 1};
}

}  // namespace

FrameTiles allTiles(int width, int height) {
  return {glm::ivec2(0), glm::ivec2(static_cast<int>(gl::groups2D(width)),
                                    static_cast<int>(gl::groups2D(height)))};
}

FrameTiles surfaceTiles(const Bounds& worldBounds, const glm::mat4& viewProjection, int width,
                        int height, float marginPixels) {
  if (worldBounds.empty()) return {};
  glm::vec2 low(std::numeric_limits<float>::max());
  glm::vec2 high(-std::numeric_limits<float>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point((corner & 1) != 0 ? worldBounds.max.x : worldBounds.min.x,
                          (corner & 2) != 0 ? worldBounds.max.y : worldBounds.min.y,
                          (corner & 4) != 0 ? worldBounds.max.z : worldBounds.min.z);
    const glm::vec4 clip = viewProjection * glm::vec4(point, 1.0F);
    // Behind or on the camera's plane, or not a number: the corners no longer bound the box.
    if (!(clip.w > 0.0F) || !std::isfinite(clip.x) || !std::isfinite(clip.y) ||
        !std::isfinite(clip.w)) {
      return allTiles(width, height);
    }
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const glm::vec2 pixel = (ndc * 0.5F + 0.5F) * glm::vec2(width, height);
    low = glm::min(low, pixel);
    high = glm::max(high, pixel);
  }
  const float margin = std::max(marginPixels, 0.0F) + kRoundingPixels;
  if (!std::isfinite(margin)) return allTiles(width, height);
  const glm::ivec2 x = tileSpan(low.x - margin, high.x + margin, width);
  const glm::ivec2 y = tileSpan(low.y - margin, high.y + margin, height);
  return {glm::ivec2(x[0], y[0]), glm::ivec2(x[1], y[1])};
}

void dispatchTiles(GLuint program, const FrameTiles& tiles) {
  glProgramUniform2ui(program, glGetUniformLocation(program, "uFirstTile"),
                      static_cast<GLuint>(tiles.first.x), static_cast<GLuint>(tiles.first.y));
  if (tiles.empty()) return;
  glDispatchCompute(static_cast<GLuint>(tiles.count.x), static_cast<GLuint>(tiles.count.y), 1);
}

}  // namespace lgh
