// C++ mirrors of the LGH buffer layouts in glsl/include/lgh_types.glsl (std430), the build
// settings, and the CPU-side form of the level table. docs/LGH.md describes the fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "lgh/request.hpp"

namespace lgh {

inline constexpr int kLghMaxLevels = 16;

// Input point light (32 bytes): xyz position, rgb intensity; w components unused.
struct PointLight {
  glm::vec4 positionPad{0.0F};
  glm::vec4 intensityPad{0.0F};
};
static_assert(sizeof(PointLight) == 32, "PointLight must match the std430 layout");

// Output grid light (48 bytes).
struct GridLight {
  glm::vec3 center{0.0F};
  std::uint32_t level = 0;
  glm::vec3 intensity{0.0F};
  std::uint32_t vertex = 0;  // x + dims.x * (y + dims.y * z) in its level's grid
  glm::vec3 variance{0.0F};  // per axis, world units^2
  float luminance = 0.0F;
};
static_assert(sizeof(GridLight) == 48, "GridLight must match the std430 layout");

struct LghLevelGpu {
  glm::vec4 cell{0.0F};  // h_l, 1/h_l
  glm::uvec4 dims{0U};   // vertices per axis, product
  std::uint32_t offset = 0;
  std::uint32_t count = 0;
  std::uint32_t denseOffset = 0;
  std::uint32_t reserved = 0;
};
static_assert(sizeof(LghLevelGpu) == 48, "LghLevel must match the std430 layout");

struct LghLevelTableGpu {
  glm::vec4 originH1{0.0F};
  glm::vec4 boundsMaxTop{0.0F};
  std::uint32_t levelCount = 0;
  std::uint32_t totalLights = 0;
  std::uint32_t inputCount = 0;
  std::uint32_t contributingCount = 0;
  std::uint32_t invalidCount = 0;
  std::uint32_t requestedLevels = 0;
  std::uint32_t fitLevels = 0;
  std::uint32_t overflow = 0;
  float maxIntensity = 0.0F;
  float fixedScale = 0.0F;
  float invFixedScale = 0.0F;
  std::uint32_t flags = 0;
  std::uint32_t candidateS1[kLghMaxLevels] = {};
  LghLevelGpu level[kLghMaxLevels];
};
static_assert(sizeof(LghLevelTableGpu) == 912, "LghLevelTable must match the std430 layout");
static_assert(offsetof(LghLevelTableGpu, levelCount) == 32);
static_assert(offsetof(LghLevelTableGpu, maxIntensity) == 64);
static_assert(offsetof(LghLevelTableGpu, candidateS1) == 80);
static_assert(offsetof(LghLevelTableGpu, level) == 144);

inline constexpr std::uint32_t kLghFlagAutoLevels = 1;
inline constexpr std::uint32_t kLghFlagFixedPoint = 2;
inline constexpr std::uint32_t kLghFlagGather = 4;

// glDrawArraysIndirect command (16 bytes). The draw buffer holds kLghDrawCommands of them.
struct DrawArraysIndirectCommand {
  std::uint32_t count = 0;
  std::uint32_t instanceCount = 0;
  std::uint32_t first = 0;
  std::uint32_t baseInstance = 0;
};
static_assert(sizeof(DrawArraysIndirectCommand) == 16);
inline constexpr int kLghDrawFromStart = 0;  // levels drawStartLevel..L
inline constexpr int kLghDrawBelowTop = 17;  // levels drawStartLevel..L-1 (top drawn full-screen)
inline constexpr int kLghDrawCommands = 18;  // 1..16: level l alone
inline constexpr std::size_t lghDrawCommandOffset(int slot) {
  return static_cast<std::size_t>(slot) * sizeof(DrawArraysIndirectCommand);
}

// Rec. 709 luminance, as glsl/include/common.glsl.
inline float lghLuminance(const glm::vec3& rgb) {
  return 0.2126F * rgb.x + 0.7152F * rgb.y + 0.0722F * rgb.z;
}

// Positions and intensities beyond this (or non-finite, or negative intensity) are invalid.
inline constexpr float kLghMaxCoordinate = 1.0e30F;
bool lghValidLight(const PointLight& light);

enum class LghAtomics {
  Auto,        // float atomics when GL_NV_shader_atomic_float exists, else fixed point
  Float,       // GL_NV_shader_atomic_float (error when missing)
  FixedPoint,  // 64-bit fixed point from 32-bit integer atomics (portable, order independent)
};

// How S1 is accumulated from the input lights (docs/LGH.md, "S1 scatter and atomics").
enum class LghS1Scatter {
  Auto,    // Binned from kLghBinnedMinLights lights on, Direct below
  Direct,  // one thread per light, 8 corners x 9 global atomics (lgh_scatter.comp)
  Binned,  // counting sort by S1 tile, then per-tile sums in shared memory (lgh_bin_*.comp)
};

// Below this many lights the binned S1's two extra dependent dispatches cost more than the direct
// scatter's atomics save: the direct S1 was faster at 100K lights and the binned one at 1M
// (docs/BENCHMARKS.md, `lgh-bench construct --s1 both`); the crossover was not measured, 256K is
// a round guess between them.
inline constexpr int kLghBinnedMinLights = 262144;

struct LghBuildSettings {
  int levels = 0;  // 0: auto (largest L with |S1| < N/2); clamped to what the budget holds
  LghSettings::Method method = LghSettings::Method::Gather;
  LghAtomics atomics = LghAtomics::Auto;
  LghS1Scatter s1 = LghS1Scatter::Auto;
  bool splitLevels = false;  // gather: one dispatch (and timer pass) per level instead of one
  int drawStartLevel = 1;    // lowest level of the "from start" and "below top" draw commands
  int cubeVertexCount = 36;  // vertices per light-volume instance in the draw commands
  // Dense grid vertices over all levels (the accumulators' size); 0: lghDefaultDenseBudget(N).
  std::size_t denseVertexBudget = 0;

  static LghBuildSettings fromRequest(const LghSettings& settings);
};

// Whether a build of `lightCount` lights accumulates S1 binned (settings.s1, Auto resolved).
bool lghUseBinnedS1(const LghBuildSettings& settings, int lightCount);

// clamp(4 N, 2^18, 2^25): room for the auto levels of surface-like inputs (|S1| < N/2 with a
// quarter of the S1 grid occupied), bounded for memory.
std::size_t lghDefaultDenseBudget(std::size_t lightCount);

// The dense vertex budget a build uses: settings.denseVertexBudget (or the default), raised to
// hold an explicit level count's cube, capped at `maxBudget` (the builder passes what its buffers
// may hold, at most 2^25), block aligned. Levels that do not fit are dropped (fitLevels).
std::size_t lghResolveDenseBudget(std::size_t lightCount, const LghBuildSettings& settings,
                                  std::size_t maxBudget = std::size_t{1} << 25);

// The level table as read back to the CPU (LghBuilder::readLevels).
struct LghLevelInfo {
  int level = 0;
  float cellSize = 0.0F;
  glm::uvec3 dims{0U};
  std::uint32_t offset = 0;
  std::uint32_t count = 0;
};

struct LghLevelTable {
  int levelCount = 0;
  int requestedLevels = 0;  // 0: auto
  int fitLevels = 0;
  glm::vec3 origin{0.0F};
  glm::vec3 boundsMax{0.0F};
  float topCellSize = 0.0F;
  std::uint32_t inputCount = 0;
  std::uint32_t contributingCount = 0;
  std::uint32_t invalidCount = 0;
  std::uint32_t totalLights = 0;
  bool overflow = false;
  bool fixedPoint = false;
  bool gather = true;
  float maxIntensity = 0.0F;
  float fixedScale = 0.0F;
  std::vector<LghLevelInfo> levels;        // levels[l - 1]
  std::vector<std::uint32_t> candidateS1;  // auto: |S1| for L = index + 1 (up to fitLevels)

  static LghLevelTable fromGpu(const LghLevelTableGpu& gpu);
};

}  // namespace lgh
