// The GPU LGH build (LghBuilder on Mesa llvmpipe) against the double-precision CPU reference, level
// by level, on random, clustered, planar, lattice and demo-scene inputs, for both methods and both
// atomics paths (llvmpipe has GL_NV_shader_atomic_float, so the float path runs here too); the
// invariants on every level; degenerate inputs; buffer reuse; draw commands; the binned S1 against
// the reference and (fixed point: bit for bit) the direct S1; and the GLSL blending functions
// against their C++ mirror.
//
// Tolerances (docs/LGH.md "Tolerances"): grid lights are matched by vertex. The GPU's sums carry
// an absolute error of about 1e-6 of the level's brightest grid light (float rounding of weights
// and offsets, fixed-point resolution), so with s = (brightest luminance) / (this luminance):
// intensity within 2e-4 relative + 1e-6 of the brightest; centre within (2e-4 + 1e-6 s) h_l
// + 2e-6 of the top cell; variance within (5e-4 + 1e-6 s) h_l^2 + 1e-3 relative. Lights of
// 1e-8 of the brightest (a VPL one float ulp off a wall gives its neighbour vertex a weight of
// ~1e-7) are thus barely checked, bright ones tightly. A vertex only one side has must carry
// <= 1e-5 of the level's luminance (a light within rounding of a grid plane gives a neighbour a
// tiny weight on one side and none on the other); counts may differ by those only. Per-level
// totals equal the input total within 1e-4 relative.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>

#include "context/gl_context.hpp"
#include "gl/gpu_timer.hpp"
#include "lgh/error.hpp"
#include "lgh/testing/lgh_blend.hpp"
#include "lgh/testing/lgh_cpu_reference.hpp"
#include "lgh/testing/light_sets.hpp"
#include "lightgrid/lgh_builder.hpp"
#include "lightgrid/vpl_sampler.hpp"
#include "scene/demo_scene.hpp"
#include "test_support.hpp"

namespace lgh::embedded {
const std::map<std::string, std::string>& glslSources();
}

namespace {

using lgh::GridLight;
using lgh::LghAtomics;
using lgh::LghBuildSettings;
using lgh::LghS1Scatter;
using lgh::PointLight;
using Method = lgh::LghSettings::Method;

constexpr double kIntensityRel = 2e-4;
constexpr double kIntensityAbs = 1e-6;   // x the level's brightest light
constexpr double kSumError = 1e-6;       // absolute error of sums, x the level's brightest light
constexpr double kCenterCells = 2e-4;    // x h_l
constexpr double kCenterTop = 2e-6;      // x top cell
constexpr double kVarianceCells = 5e-4;  // x h_l^2
constexpr double kVarianceRel = 1e-3;
constexpr double kUnmatchedRel = 1e-5;  // x the level's total luminance
constexpr double kTotalRel = 1e-4;

struct GpuResult {
  lgh::LghLevelTable table;
  std::vector<GridLight> lights;
  std::vector<lgh::DrawArraysIndirectCommand> draws;
};

LghBuildSettings settings(int levels, Method method, LghAtomics atomics,
                          LghS1Scatter s1 = LghS1Scatter::Auto) {
  LghBuildSettings s;
  s.levels = levels;
  s.method = method;
  s.atomics = atomics;
  s.s1 = s1;
  return s;
}

const char* s1Name(LghS1Scatter s1) {
  switch (s1) {
    case LghS1Scatter::Direct:
      return "direct S1";
    case LghS1Scatter::Binned:
      return "binned S1";
    case LghS1Scatter::Auto:
      break;
  }
  return "auto S1";
}

std::string describe(const LghBuildSettings& s) {
  return fmt::format("levels {} {} {} {}", s.levels,
                     s.method == Method::Gather ? "gather" : "scatter",
                     s.atomics == LghAtomics::FixedPoint ? "fixed-point" : "float", s1Name(s.s1));
}

class LghBuild : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    builder = std::make_unique<lgh::LghBuilder>();
    buffer = std::make_unique<lgh::gl::SizedBuffer>();
  }
  static void TearDownTestSuite() {
    buffer.reset();
    builder.reset();
    context.reset();
  }

  // Uploads without the CPU check (so invalid lights reach the GPU).
  static void uploadRaw(const std::vector<PointLight>& lights) {
    const auto bytes = static_cast<GLsizeiptr>(lights.size() * sizeof(PointLight));
    buffer->reserve(std::max<GLsizeiptr>(bytes, 32));
    if (bytes > 0) glNamedBufferSubData(buffer->id(), 0, bytes, lights.data());
  }

  static GpuResult build(const std::vector<PointLight>& lights, const LghBuildSettings& s) {
    uploadRaw(lights);
    builder->build(buffer->id(), static_cast<int>(lights.size()), s);
    return {builder->readLevels(), builder->readGridLights(), builder->readDrawCommands()};
  }

  static void expectInvariants(const std::vector<PointLight>& lights, const GpuResult& gpu) {
    const glm::dvec3 total = lgh::totalIntensity(lights);
    const auto& t = gpu.table;
    const double slack = 1e-5 * t.topCellSize;
    for (const auto& level : t.levels) {
      glm::dvec3 sum(0.0);
      for (std::uint32_t i = level.offset; i < level.offset + level.count; ++i) {
        const GridLight& light = gpu.lights[i];
        ASSERT_EQ(light.level, static_cast<std::uint32_t>(level.level));
        sum += glm::dvec3(light.intensity);
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(light.center[a], t.origin[a] - slack);
          EXPECT_LE(light.center[a], t.boundsMax[a] + slack);
          EXPECT_GE(light.variance[a], 0.0F);
        }
        EXPECT_GT(light.luminance, 0.0F);
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sum[c], total[c], kTotalRel * total[c]) << "level " << level.level;
      }
    }
    if (t.levelCount > 0) EXPECT_LE(t.levels.back().count, 8U);
    EXPECT_FALSE(t.overflow);
  }

  static void compareLevel(const GpuResult& gpu, const lgh::LghReference& ref, int l) {
    const auto& info = gpu.table.levels[l - 1];
    const auto& expected = ref.levels[l - 1];
    ASSERT_EQ(info.dims, expected.dims) << "level " << l;
    EXPECT_FLOAT_EQ(info.cellSize, static_cast<float>(expected.cellSize));
    double levelLum = 0.0;
    double maxLum = 0.0;
    for (const auto& light : expected.lights) {
      levelLum += light.luminance;
      maxLum = std::max(maxLum, light.luminance);
    }
    const double h = expected.cellSize;
    const double top = ref.grid.top;
    std::size_t i = info.offset;
    const std::size_t end = info.offset + info.count;
    std::size_t j = 0;
    std::size_t unmatched = 0;
    auto negligible = [&](double luminance) {
      ++unmatched;
      EXPECT_LE(luminance, kUnmatchedRel * levelLum) << "unmatched grid light, level " << l;
    };
    while (i < end || j < expected.lights.size()) {
      if (j == expected.lights.size() ||
          (i < end && gpu.lights[i].vertex < expected.lights[j].vertex)) {
        negligible(gpu.lights[i++].luminance);
        continue;
      }
      if (i == end || expected.lights[j].vertex < gpu.lights[i].vertex) {
        negligible(expected.lights[j++].luminance);
        continue;
      }
      const GridLight& g = gpu.lights[i++];
      const auto& r = expected.lights[j++];
      const double significance = kSumError * maxLum / r.luminance;
      if (i > info.offset + 1) {
        ASSERT_LT(gpu.lights[i - 2].vertex, g.vertex) << "not in vertex order";
      }
      for (int a = 0; a < 3; ++a) {
        ASSERT_NEAR(g.intensity[a], r.intensity[a],
                    kIntensityRel * r.intensity[a] + kIntensityAbs * maxLum)
            << "level " << l << " vertex " << g.vertex;
        ASSERT_NEAR(g.center[a], r.center[a], (kCenterCells + significance) * h + kCenterTop * top)
            << "level " << l << " vertex " << g.vertex << " axis " << a;
        ASSERT_NEAR(g.variance[a], r.variance[a],
                    (kVarianceCells + significance) * h * h + kVarianceRel * r.variance[a])
            << "level " << l << " vertex " << g.vertex << " axis " << a;
      }
    }
    EXPECT_LE(unmatched, std::max<std::size_t>(2, expected.lights.size() / 500)) << "level " << l;
  }

  // Builds on the GPU and compares with the CPU reference level by level.
  static GpuResult expectMatchesReference(const std::vector<PointLight>& lights,
                                          const LghBuildSettings& s) {
    SCOPED_TRACE(describe(s));
    GpuResult gpu = build(lights, s);
    const lgh::LghReference ref =
        lgh::buildLghReference(lights, s, builder->denseBudget(static_cast<int>(lights.size()), s));
    EXPECT_EQ(gpu.table.levelCount, ref.levelCount);
    EXPECT_EQ(gpu.table.fitLevels, ref.levelCount == 0 ? 0 : ref.fitLevels);
    EXPECT_EQ(gpu.table.contributingCount, ref.contributingCount);
    EXPECT_EQ(gpu.table.origin, ref.grid.origin);
    EXPECT_EQ(gpu.table.topCellSize, ref.grid.top);
    if (s.levels == 0) EXPECT_EQ(gpu.table.candidateS1, ref.candidateS1);
    if (gpu.table.levelCount != ref.levelCount) return gpu;
    for (int l = 1; l <= ref.levelCount; ++l) compareLevel(gpu, ref, l);
    expectInvariants(lights, gpu);
    return gpu;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::LghBuilder> builder;
  static inline std::unique_ptr<lgh::gl::SizedBuffer> buffer;
};

PointLight light(glm::vec3 p, glm::vec3 c) {
  PointLight l;
  l.positionPad = glm::vec4(p, 0.0F);
  l.intensityPad = glm::vec4(c, 0.0F);
  return l;
}

const LghAtomics kAtomics[] = {LghAtomics::FixedPoint, LghAtomics::Auto};

// `count` lights uniform in a cube of edge 2 r around `centre`.
std::vector<PointLight> cubeCluster(int count, glm::vec3 centre, float r, std::uint32_t seed) {
  return lgh::uniformLights(count, centre - glm::vec3(r), centre + glm::vec3(r), seed);
}

std::vector<PointLight> concat(std::vector<PointLight> a, const std::vector<PointLight>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST_F(LghBuild, UsesFloatAtomicsWhereAvailable) {
  // llvmpipe (Mesa 25) has GL_NV_shader_atomic_float: both paths get tested here.
  GpuResult gpu = build(lgh::uniformLights(100, {0, 0, 0}, {1, 1, 1}, 1),
                        settings(3, Method::Gather, LghAtomics::Auto));
  EXPECT_EQ(gpu.table.fixedPoint, !builder->floatAtomicsAvailable());
}

TEST_F(LghBuild, RandomUniformAutoLevels) {
  const auto lights = lgh::uniformLights(8000, {-2, 0, -1}, {3, 1.5F, 1}, 21, 5.0F);
  for (LghAtomics atomics : kAtomics) {
    expectMatchesReference(lights, settings(0, Method::Gather, atomics));
  }
}

TEST_F(LghBuild, ClusteredExplicitLevels) {
  const auto lights = lgh::clusteredLights(6000, 7, 0.03F, {0, 0, 0}, {4, 4, 4}, 5);
  for (LghAtomics atomics : kAtomics) {
    expectMatchesReference(lights, settings(6, Method::Gather, atomics));
  }
}

TEST_F(LghBuild, DemoSceneVplsBothMethods) {
  const auto lights = lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {10000, 3, 10.0F});
  for (Method method : {Method::Gather, Method::Scatter}) {
    for (LghAtomics atomics : kAtomics) {
      expectMatchesReference(lights, settings(0, method, atomics));
    }
  }
}

TEST_F(LghBuild, PlaneAndLattice) {
  const auto plane = lgh::planeLights(4000, {-1, 0.25F, -1}, {2, 0, 0}, {0, 0, 2}, 8);
  // 9^3 lights exactly on the S1 vertices of a 4-level grid (h1 = spacing), and on coarser ones.
  const auto lattice = lgh::latticeLights(9, {-1, -1, -1}, 0.25F, 9);
  for (LghAtomics atomics : kAtomics) {
    expectMatchesReference(plane, settings(0, Method::Gather, atomics));
    expectMatchesReference(lattice, settings(4, Method::Gather, atomics));
    expectMatchesReference(lattice, settings(4, Method::Scatter, atomics));
    expectMatchesReference(lattice, settings(0, Method::Gather, atomics));
  }
}

TEST_F(LghBuild, ManyLevelsUseTheCooperativeGather) {
  // 7 levels: levels >= 4 gather with one work group per (vertex, chunk of rows), several chunks
  // per vertex from level 5 on.
  const auto lights = lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {20000, 4, 10.0F});
  for (LghAtomics atomics : kAtomics) {
    expectMatchesReference(lights, settings(7, Method::Gather, atomics));
  }
}

TEST_F(LghBuild, SplitLevelsEqualsOneDispatch) {
  const auto lights = lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {5000, 6, 10.0F});
  LghBuildSettings s = settings(0, Method::Gather, LghAtomics::FixedPoint);
  const GpuResult one = build(lights, s);
  s.splitLevels = true;
  lgh::gl::GpuTimer timer;
  builder->build(buffer->id(), static_cast<int>(lights.size()), s, &timer);
  lgh::TimingTable timings;
  timer.collect(timings);
  const auto split = builder->readGridLights();
  ASSERT_EQ(split.size(), one.lights.size());
  // Fixed point sums are exact and order independent: bit-identical results.
  EXPECT_EQ(0, std::memcmp(split.data(), one.lights.data(), split.size() * sizeof(GridLight)));
  for (const char* pass :
       {"lgh bounds", "lgh auto levels", "lgh S1", "lgh S1 compact", "lgh S2", "lgh merge"}) {
    EXPECT_GE(timings.get(pass), 0.0) << pass;
  }
}

TEST_F(LghBuild, RebuildAfterOtherInputsIsIdentical) {
  // The compaction clears the accumulators it consumed; a stale value would show up here.
  const auto a = lgh::uniformLights(3000, {0, 0, 0}, {1, 2, 3}, 31);
  const auto b = lgh::clusteredLights(12000, 3, 0.2F, {-5, -5, -5}, {5, 5, 5}, 32);
  for (Method method : {Method::Gather, Method::Scatter}) {
    const LghBuildSettings s = settings(0, method, LghAtomics::FixedPoint);
    const GpuResult first = build(a, s);
    build(b, settings(7, method, LghAtomics::FixedPoint));
    build(b, settings(0, method, LghAtomics::Auto));
    const GpuResult again = build(a, s);
    ASSERT_EQ(first.lights.size(), again.lights.size());
    EXPECT_EQ(0, std::memcmp(first.lights.data(), again.lights.data(),
                             first.lights.size() * sizeof(GridLight)));
  }
}

TEST_F(LghBuild, EmptyInputDrawsNothing) {
  LghBuildSettings s = settings(0, Method::Gather, LghAtomics::Auto);
  build(lgh::uniformLights(500, {0, 0, 0}, {1, 1, 1}, 2), s);  // leave non-empty state behind
  const GpuResult gpu = build({}, s);
  EXPECT_EQ(gpu.table.levelCount, 0);
  EXPECT_EQ(gpu.table.totalLights, 0U);
  EXPECT_EQ(gpu.table.inputCount, 0U);
  ASSERT_EQ(gpu.draws.size(), static_cast<std::size_t>(lgh::kLghDrawCommands));
  for (const auto& draw : gpu.draws) {
    EXPECT_EQ(draw.instanceCount, 0U);
    EXPECT_EQ(draw.count, 36U);
  }
}

TEST_F(LghBuild, DegenerateInputs) {
  const std::vector<std::vector<PointLight>> sets{
      {light({1, 2, 3}, {1, 0.5F, 0.25F})},                                 // one light
      std::vector<PointLight>(300, light({-4, 0, 9}, {0.1F, 0.1F, 0.1F})),  // all at one point
      lgh::planeLights(2000, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4),           // zero extent along z
      lgh::planeLights(500, {0, 0, 0}, {2, 0, 0}, {0, 0, 0}, 5)};           // on a line (y, z flat)
  for (const auto& lights : sets) {
    for (Method method : {Method::Gather, Method::Scatter}) {
      for (int levels : {0, 3}) {
        const GpuResult gpu =
            expectMatchesReference(lights, settings(levels, method, LghAtomics::Auto));
        ASSERT_GE(gpu.table.levelCount, 1);
        if (lights.size() == 1 || lights[0].positionPad == lights.back().positionPad) {
          for (const auto& level : gpu.table.levels) EXPECT_EQ(level.count, 1U);
        }
      }
    }
  }
}

TEST_F(LghBuild, ZeroIntensitiesAreDropped) {
  auto lights = lgh::uniformLights(2000, {0, 0, 0}, {1, 1, 1}, 12);
  for (std::size_t i = 0; i < lights.size(); i += 3) lights[i].intensityPad = glm::vec4(0.0F);
  const GpuResult gpu =
      expectMatchesReference(lights, settings(0, Method::Gather, LghAtomics::Auto));
  EXPECT_EQ(gpu.table.contributingCount, 1333U);

  std::vector<PointLight> dark(100, light({1, 1, 1}, {0, 0, 0}));
  const GpuResult none = build(dark, settings(0, Method::Gather, LghAtomics::Auto));
  EXPECT_EQ(none.table.levelCount, 0);
  EXPECT_EQ(none.table.totalLights, 0U);
  EXPECT_EQ(none.draws[lgh::kLghDrawFromStart].instanceCount, 0U);
}

TEST_F(LghBuild, InvalidLightsAreRejected) {
  auto lights = lgh::uniformLights(1000, {0, 0, 0}, {1, 1, 1}, 13);
  lights[417].positionPad.y = std::numeric_limits<float>::quiet_NaN();
  lights[800].intensityPad.x = std::numeric_limits<float>::infinity();
  EXPECT_THROW(lgh::uploadPointLights(lights, *buffer), lgh::Error);
  uploadRaw(lights);
  try {
    builder->validate(buffer->id(), static_cast<int>(lights.size()));
    ADD_FAILURE() << "validate accepted NaN/inf lights";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid);
    EXPECT_NE(std::string(error.what()).find("2 of 1000"), std::string::npos) << error.what();
  }
  const GpuResult gpu = build(lights, settings(0, Method::Gather, LghAtomics::Auto));
  EXPECT_EQ(gpu.table.invalidCount, 2U);
  EXPECT_EQ(gpu.table.levelCount, 0);
  EXPECT_EQ(gpu.draws[lgh::kLghDrawFromStart].instanceCount, 0U);
  lights[417].positionPad.y = 0.5F;
  lights[800].intensityPad.x = 0.5F;
  uploadRaw(lights);
  EXPECT_NO_THROW(builder->validate(buffer->id(), static_cast<int>(lights.size())));
}

TEST_F(LghBuild, DrawCommandsFollowTheLevelTable) {
  const auto lights = lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {4000, 7, 10.0F});
  LghBuildSettings s = settings(5, Method::Gather, LghAtomics::Auto);
  s.drawStartLevel = 2;
  s.cubeVertexCount = 14;
  const GpuResult gpu = build(lights, s);
  const auto& levels = gpu.table.levels;
  ASSERT_EQ(levels.size(), 5U);
  std::uint32_t fromStart = 0;
  for (int l = 1; l <= 5; ++l) {
    const auto& draw = gpu.draws[l];
    EXPECT_EQ(draw.count, 14U);
    EXPECT_EQ(draw.instanceCount, levels[l - 1].count);
    EXPECT_EQ(draw.baseInstance, levels[l - 1].offset);
    if (l >= 2) fromStart += levels[l - 1].count;
    if (l > 1) EXPECT_EQ(levels[l - 1].offset, levels[l - 2].offset + levels[l - 2].count);
  }
  EXPECT_EQ(gpu.draws[lgh::kLghDrawFromStart].instanceCount, fromStart);
  EXPECT_EQ(gpu.draws[lgh::kLghDrawFromStart].baseInstance, levels[1].offset);
  EXPECT_EQ(gpu.draws[lgh::kLghDrawBelowTop].instanceCount, fromStart - levels[4].count);
  for (int l = 6; l <= lgh::kLghMaxLevels; ++l) EXPECT_EQ(gpu.draws[l].instanceCount, 0U);
  EXPECT_EQ(gpu.table.totalLights, levels[4].offset + levels[4].count);
}

// ---- binned S1 ---------------------------------------------------------------------------

TEST_F(LghBuild, BinnedS1MatchesReference) {
  const auto uniform = lgh::uniformLights(8000, {-2, 0, -1}, {3, 1.5F, 1}, 21, 5.0F);
  const auto clustered = lgh::clusteredLights(6000, 7, 0.03F, {0, 0, 0}, {4, 4, 4}, 5);
  const auto plane = lgh::planeLights(4000, {-1, 0.25F, -1}, {2, 0, 0}, {0, 0, 2}, 8);
  const auto lattice = lgh::latticeLights(9, {-1, -1, -1}, 0.25F, 9);
  const auto vpls = lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {10000, 3, 10.0F});
  for (LghAtomics atomics : kAtomics) {
    expectMatchesReference(uniform, settings(0, Method::Gather, atomics, LghS1Scatter::Binned));
    expectMatchesReference(clustered, settings(6, Method::Gather, atomics, LghS1Scatter::Binned));
    expectMatchesReference(plane, settings(0, Method::Gather, atomics, LghS1Scatter::Binned));
    expectMatchesReference(lattice, settings(4, Method::Gather, atomics, LghS1Scatter::Binned));
    expectMatchesReference(lattice, settings(4, Method::Scatter, atomics, LghS1Scatter::Binned));
    for (Method method : {Method::Gather, Method::Scatter}) {
      expectMatchesReference(vpls, settings(0, method, atomics, LghS1Scatter::Binned));
    }
  }
}

TEST_F(LghBuild, BinnedS1BigTilesAreChunked) {
  // 3 levels: S1 has 4 cells per axis, one tile: 20000 lights in 20 chunks of one tile.
  const auto one = lgh::uniformLights(20000, {0, 0, 0}, {1, 1, 1}, 41);
  // 6 levels (S1: 32 cells per axis): 30000 lights inside one S1 tile (cells 10.1..10.5 of 32,
  // within a tile for T = 8 and T = 6 alike) among 2000 spread over the whole grid.
  const auto hot = concat(cubeCluster(30000, glm::vec3(10.3F / 32.0F), 0.005F, 42),
                          lgh::uniformLights(2000, {0, 0, 0}, {1, 1, 1}, 43));
  for (LghAtomics atomics : kAtomics) {
    expectMatchesReference(one, settings(3, Method::Gather, atomics, LghS1Scatter::Binned));
    expectMatchesReference(hot, settings(6, Method::Gather, atomics, LghS1Scatter::Binned));
    expectMatchesReference(hot, settings(0, Method::Gather, atomics, LghS1Scatter::Binned));
  }
}

TEST_F(LghBuild, BinnedS1DegenerateInputs) {
  const std::vector<std::vector<PointLight>> sets{
      {light({1, 2, 3}, {1, 0.5F, 0.25F})},                                 // one light
      std::vector<PointLight>(300, light({-4, 0, 9}, {0.1F, 0.1F, 0.1F})),  // all at one point
      lgh::planeLights(2000, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4),           // zero extent along z
      lgh::planeLights(500, {0, 0, 0}, {2, 0, 0}, {0, 0, 0}, 5)};           // on a line (y, z flat)
  for (const auto& lights : sets) {
    for (LghAtomics atomics : kAtomics) {
      for (int levels : {0, 3, 9}) {
        const GpuResult gpu = expectMatchesReference(
            lights, settings(levels, Method::Gather, atomics, LghS1Scatter::Binned));
        ASSERT_GE(gpu.table.levelCount, 1);
      }
    }
  }
  const LghBuildSettings s = settings(0, Method::Gather, LghAtomics::Auto, LghS1Scatter::Binned);
  const GpuResult empty = build({}, s);
  EXPECT_EQ(empty.table.levelCount, 0);
  EXPECT_EQ(empty.draws[lgh::kLghDrawFromStart].instanceCount, 0U);
  const GpuResult dark = build(std::vector<PointLight>(100, light({1, 1, 1}, {0, 0, 0})), s);
  EXPECT_EQ(dark.table.levelCount, 0);
  EXPECT_EQ(dark.table.totalLights, 0U);
  auto invalid = lgh::uniformLights(1000, {0, 0, 0}, {1, 1, 1}, 13);
  invalid[5].positionPad.x = std::numeric_limits<float>::quiet_NaN();
  const GpuResult rejected = build(invalid, s);
  EXPECT_EQ(rejected.table.invalidCount, 1U);
  EXPECT_EQ(rejected.table.levelCount, 0);
}

// Fixed point: both S1 paths sum the same 64-bit integers, exactly: bit-identical grid lights.
TEST_F(LghBuild, BinnedS1FixedPointEqualsDirect) {
  const std::vector<std::vector<PointLight>> sets{
      lgh::uniformLights(8000, {-2, 0, -1}, {3, 1.5F, 1}, 21, 5.0F),
      lgh::clusteredLights(6000, 7, 0.03F, {0, 0, 0}, {4, 4, 4}, 5),
      lgh::planeLights(4000, {-1, 0.25F, -1}, {2, 0, 0}, {0, 0, 2}, 8),
      lgh::latticeLights(9, {-1, -1, -1}, 0.25F, 9),
      lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {10000, 3, 10.0F}),
      std::vector<PointLight>(300, light({-4, 0, 9}, {0.1F, 0.1F, 0.1F})),
      // Many chunks per tile (see BinnedS1BigTilesAreChunked).
      lgh::uniformLights(20000, {0, 0, 0}, {1, 2, 1}, 41),
      concat(cubeCluster(30000, glm::vec3(10.3F / 32.0F), 0.005F, 42),
             lgh::uniformLights(2000, {0, 0, 0}, {1, 1, 1}, 43))};
  for (const auto& lights : sets) {
    for (int levels : {0, 3, 7}) {
      const GpuResult direct = build(
          lights, settings(levels, Method::Gather, LghAtomics::FixedPoint, LghS1Scatter::Direct));
      const GpuResult binned = build(
          lights, settings(levels, Method::Gather, LghAtomics::FixedPoint, LghS1Scatter::Binned));
      ASSERT_EQ(binned.table.levelCount, direct.table.levelCount);
      ASSERT_EQ(binned.lights.size(), direct.lights.size()) << "levels " << levels;
      EXPECT_EQ(0, std::memcmp(binned.lights.data(), direct.lights.data(),
                               direct.lights.size() * sizeof(GridLight)))
          << lights.size() << " lights, levels " << levels;
      EXPECT_EQ(0, std::memcmp(binned.draws.data(), direct.draws.data(),
                               direct.draws.size() * sizeof(direct.draws[0])));
    }
  }
}

TEST_F(LghBuild, BinnedS1RebuildAfterOtherInputsIsIdentical) {
  // The bin counts end at zero and the accumulators are cleared by the compaction: a stale value
  // would show up here. Float and fixed point bin with different tile sizes.
  const auto a = lgh::uniformLights(3000, {0, 0, 0}, {1, 2, 3}, 31);
  const auto b = lgh::clusteredLights(12000, 3, 0.2F, {-5, -5, -5}, {5, 5, 5}, 32);
  const LghBuildSettings s =
      settings(0, Method::Gather, LghAtomics::FixedPoint, LghS1Scatter::Binned);
  const GpuResult first = build(a, s);
  build(b, settings(7, Method::Gather, LghAtomics::FixedPoint, LghS1Scatter::Binned));
  build(b, settings(0, Method::Scatter, LghAtomics::Auto, LghS1Scatter::Binned));
  build(a, settings(5, Method::Gather, LghAtomics::Auto, LghS1Scatter::Direct));
  const GpuResult again = build(a, s);
  ASSERT_EQ(first.lights.size(), again.lights.size());
  EXPECT_EQ(0, std::memcmp(first.lights.data(), again.lights.data(),
                           first.lights.size() * sizeof(GridLight)));
}

TEST_F(LghBuild, AutoS1BinsLargeInputs) {
  // Past kLghBinnedMinLights the default is the binned S1: same result as the direct one.
  const auto lights =
      lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {lgh::kLghBinnedMinLights, 5, 10.0F});
  ASSERT_TRUE(lgh::lghUseBinnedS1(LghBuildSettings{}, static_cast<int>(lights.size())));
  const GpuResult automatic =
      expectMatchesReference(lights, settings(0, Method::Gather, LghAtomics::FixedPoint));
  const GpuResult direct =
      build(lights, settings(0, Method::Gather, LghAtomics::FixedPoint, LghS1Scatter::Direct));
  ASSERT_EQ(automatic.lights.size(), direct.lights.size());
  EXPECT_EQ(0, std::memcmp(automatic.lights.data(), direct.lights.data(),
                           direct.lights.size() * sizeof(GridLight)));
  expectMatchesReference(lights, settings(0, Method::Gather, LghAtomics::Auto));
}

TEST_F(LghBuild, BlendGlslMatchesCpp) {
  const auto& sources = lgh::embedded::glslSources();
  // The raw texts, without the shader library: lgh_types.glsl's one include is pasted in front.
  std::string types = sources.at("include/lgh_types.glsl");
  const std::string include = "#include \"include/slots.glsl\"";
  ASSERT_NE(types.find(include), std::string::npos);
  types.erase(types.find(include), include.size());
  const std::string source = "#version 450\n" + sources.at("include/slots.glsl") + types +
                             sources.at("include/lgh_blend.glsl") + R"(
layout(local_size_x = 64) in;
struct Query { float d; int level; int start; int top; float alpha; float h1; float pad0; float pad1; };
layout(std430, binding = 0) readonly buffer Queries { Query queries[]; };
layout(std430, binding = 1) writeonly buffer Results { float results[]; };
layout(std430, binding = 2) readonly buffer Levels { LghLevelTable lgh; };  // public types compile
uniform uint u_count;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Query q = queries[i];
  results[i] = lghBlend(q.d, q.level, q.start, q.top, q.alpha, q.h1);
}
)";
  struct Query {
    float d;
    int level, start, top;
    float alpha, h1, pad0 = 0, pad1 = 0;
  };
  std::vector<Query> queries;
  for (float alpha : {0.5F, 1.0F, 2.0F}) {
    for (int top = 1; top <= 6; ++top) {
      for (int start = 1; start <= top; ++start) {
        for (int level = start; level <= top; ++level) {
          for (int k = 0; k <= 64; ++k) {
            const float d = 2.2F * lgh::lghRadius(top, alpha, 0.3F) * static_cast<float>(k) / 64.0F;
            queries.push_back({d, level, start, top, alpha, 0.3F});
          }
        }
      }
    }
  }
  lgh::gl::Shader shader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  ASSERT_EQ(ok, GL_TRUE) << "lgh_blend.glsl failed to compile";
  lgh::gl::Program program;
  glAttachShader(program.id(), shader.id());
  glLinkProgram(program.id());
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  ASSERT_EQ(ok, GL_TRUE);
  lgh::gl::SizedBuffer in;
  lgh::gl::SizedBuffer out;
  lgh::gl::SizedBuffer levels;
  in.reserve(static_cast<GLsizeiptr>(queries.size() * sizeof(Query)));
  glNamedBufferSubData(in.id(), 0, in.size, queries.data());
  out.reserve(static_cast<GLsizeiptr>(queries.size() * sizeof(float)));
  levels.reserve(sizeof(lgh::LghLevelTableGpu));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, levels.id());
  glUseProgram(program.id());
  glProgramUniform1ui(program.id(), glGetUniformLocation(program.id(), "u_count"),
                      static_cast<GLuint>(queries.size()));
  glDispatchCompute(static_cast<GLuint>((queries.size() + 63) / 64), 1, 1);
  glUseProgram(0);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> results(queries.size());
  glGetNamedBufferSubData(out.id(), 0, out.size, results.data());
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    ASSERT_NEAR(results[i], lgh::lghBlend(q.d, q.level, q.start, q.top, q.alpha, q.h1), 1e-5F)
        << "d " << q.d << " level " << q.level << " of " << q.start << ".." << q.top;
  }
}

}  // namespace
