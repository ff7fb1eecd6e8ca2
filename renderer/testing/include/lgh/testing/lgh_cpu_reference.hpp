// A straightforward CPU reference of the LGH build, in double precision, implementing the same
// definitions as the GPU kernels (docs/LGH.md): the same grid (computed in float exactly as the
// kernels do, so both place every light in the same cell), S1 by scatter, S2..SL either gathered
// from S1 (each S1 grid light a point light at its centre) or scattered from the input lights,
// the same auto-level rule, and the same finalisation of centres and variances. Loops are plain:
// the gather visits every S1 vertex of each vertex's support box. For tests and small inputs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "lightgrid/lgh_types.hpp"

namespace lgh {

// The grid as the kernels fix it (float arithmetic, mirrored operation by operation).
struct LghGridGeometry {
  glm::vec3 origin{0.0F};  // min corner of the contributing lights' bounds
  glm::vec3 boundsMax{0.0F};
  glm::vec3 extent{0.0F};  // boundsMax - origin
  float top = 0.0F;        // top cell size: the longest edge, at least the minimum extent
  float invTop = 0.0F;     // 1 / top

  static LghGridGeometry fromBounds(const glm::vec3& lo, const glm::vec3& hi);
  // Vertices per axis of a grid with 2^e cells along the longest axis.
  glm::uvec3 dims(int e) const;
  // Dense vertices (block aligned) of all levels of an L-level hierarchy.
  std::size_t denseTotal(int levels) const;
  // The most levels (<= 16) whose dense grids fit `budget`.
  int fitLevels(std::size_t budget) const;
  // Grid coordinate of p in a grid with 2^e cells: min((p - origin) * invTop * 2^e, 2^e).
  glm::vec3 gridCoordinate(const glm::vec3& p, int e) const;
};

struct LghReferenceLight {
  std::uint32_t vertex = 0;  // x + dims.x * (y + dims.y * z)
  glm::uvec3 coords{0U};
  glm::dvec3 center{0.0};
  glm::dvec3 intensity{0.0};
  glm::dvec3 variance{0.0};
  double luminance = 0.0;
  glm::dvec3 offsetCells{0.0};    // (center - vertex) / h
  glm::dvec3 varianceCells{0.0};  // variance / h^2
};

struct LghReferenceLevel {
  int level = 0;
  double cellSize = 0.0;
  glm::uvec3 dims{0U};
  std::vector<LghReferenceLight> lights;  // in vertex order, as the GPU compacts them
};

struct LghReference {
  int levelCount = 0;
  int fitLevels = 0;
  LghGridGeometry grid;
  std::size_t contributingCount = 0;
  glm::dvec3 totalIntensity{0.0};          // sum of the contributing lights' rgb
  std::vector<std::uint32_t> candidateS1;  // auto levels: |S1| for L = index + 1
  std::vector<LghReferenceLevel> levels;   // levels[l - 1]
};

// Throws lgh::Error(Invalid) for invalid lights (as LghBuilder::validate). The dense vertex
// budget decides how many levels fit: `denseBudget`, or when 0 lghResolveDenseBudget(N,
// settings); pass LghBuilder::denseBudget() for the GPU's choices (its buffers may cap it).
LghReference buildLghReference(const std::vector<PointLight>& lights,
                               const LghBuildSettings& settings, std::size_t denseBudget = 0);

}  // namespace lgh
