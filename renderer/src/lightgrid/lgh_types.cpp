#include "lightgrid/lgh_types.hpp"

#include <algorithm>
#include <cmath>

namespace lgh {

bool lghValidLight(const PointLight& light) {
  for (int a = 0; a < 3; ++a) {
    const float p = light.positionPad[a];
    const float c = light.intensityPad[a];
    if (!std::isfinite(p) || !std::isfinite(c)) return false;
    if (std::fabs(p) > kLghMaxCoordinate || c < 0.0F || c > kLghMaxCoordinate) return false;
  }
  return true;
}

LghBuildSettings LghBuildSettings::fromRequest(const LghSettings& settings) {
  LghBuildSettings build;
  build.levels = settings.levels;
  build.method = settings.method;
  return build;
}

bool lghUseBinnedS1(const LghBuildSettings& settings, int lightCount) {
  switch (settings.s1) {
    case LghS1Scatter::Direct:
      return false;
    case LghS1Scatter::Binned:
      return true;
    case LghS1Scatter::Auto:
      break;
  }
  return lightCount >= kLghBinnedMinLights;
}

std::size_t lghDefaultDenseBudget(std::size_t lightCount) {
  return std::clamp<std::size_t>(4 * lightCount, std::size_t{1} << 18, std::size_t{1} << 25);
}

std::size_t lghResolveDenseBudget(std::size_t lightCount, const LghBuildSettings& settings,
                                  std::size_t maxBudget) {
  constexpr std::size_t kBlock = 1024;
  std::size_t budget = settings.denseVertexBudget > 0 ? settings.denseVertexBudget
                                                      : lghDefaultDenseBudget(lightCount);
  if (settings.levels > 0) {
    std::size_t cube = 0;  // every level of an L-level grid over a cube
    for (int e = 0; e < std::min(settings.levels, kLghMaxLevels); ++e) {
      const std::size_t side = (std::size_t{1} << e) + 1;
      cube += (side * side * side + kBlock - 1) / kBlock * kBlock;
    }
    budget = std::max(budget, cube);
  }
  budget = std::min({budget, maxBudget, std::size_t{1} << 25});
  return std::max<std::size_t>(budget, kLghMaxLevels * kBlock) / kBlock * kBlock;
}

LghLevelTable LghLevelTable::fromGpu(const LghLevelTableGpu& gpu) {
  LghLevelTable table;
  table.levelCount = static_cast<int>(std::min<std::uint32_t>(gpu.levelCount, kLghMaxLevels));
  table.requestedLevels = static_cast<int>(gpu.requestedLevels);
  table.fitLevels = static_cast<int>(std::min<std::uint32_t>(gpu.fitLevels, kLghMaxLevels));
  table.origin = glm::vec3(gpu.originH1);
  table.boundsMax = glm::vec3(gpu.boundsMaxTop);
  table.topCellSize = gpu.boundsMaxTop.w;
  table.inputCount = gpu.inputCount;
  table.contributingCount = gpu.contributingCount;
  table.invalidCount = gpu.invalidCount;
  table.totalLights = gpu.totalLights;
  table.overflow = gpu.overflow != 0;
  table.fixedPoint = (gpu.flags & kLghFlagFixedPoint) != 0;
  table.gather = (gpu.flags & kLghFlagGather) != 0;
  table.maxIntensity = gpu.maxIntensity;
  table.fixedScale = gpu.fixedScale;
  for (int l = 1; l <= table.levelCount; ++l) {
    const LghLevelGpu& level = gpu.level[l - 1];
    table.levels.push_back({l, level.cell.x, glm::uvec3(level.dims), level.offset, level.count});
  }
  if ((gpu.flags & kLghFlagAutoLevels) != 0) {
    table.candidateS1.assign(gpu.candidateS1, gpu.candidateS1 + table.fitLevels);
  }
  return table;
}

}  // namespace lgh
