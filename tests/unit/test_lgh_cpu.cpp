// The CPU reference of the LGH build (renderer/testing: lgh/testing/lgh_cpu_reference.hpp) and
// the VPL sampler: hand-computed cases, the invariants every level must keep (total intensity of
// the input, centres inside the lights' bounds, variance >= 0, top level <= 8 lights), the
// paper's auto-level rule, degenerate inputs. Tolerances: 1e-9 relative (double sums of float
// inputs).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "lgh/error.hpp"
#include "lgh/testing/lgh_cpu_reference.hpp"
#include "lgh/testing/light_sets.hpp"
#include "lightgrid/vpl_sampler.hpp"
#include "scene/demo_scene.hpp"

namespace {

using lgh::LghBuildSettings;
using lgh::LghReference;
using lgh::PointLight;
using Method = lgh::LghSettings::Method;

PointLight light(glm::vec3 p, glm::vec3 c) {
  PointLight l;
  l.positionPad = glm::vec4(p, 0.0F);
  l.intensityPad = glm::vec4(c, 0.0F);
  return l;
}

LghBuildSettings settings(int levels, Method method = Method::Gather) {
  LghBuildSettings s;
  s.levels = levels;
  s.method = method;
  return s;
}

void expectInvariants(const std::vector<PointLight>& lights, const LghReference& ref) {
  const glm::dvec3 total = lgh::totalIntensity(lights);
  // Light positions reach the grid through float coordinates t = (p - origin) / h: ~1e-7 relative.
  const double slack = 1.0e-6 * ref.grid.top;
  for (const auto& level : ref.levels) {
    glm::dvec3 sum(0.0);
    for (const auto& l : level.lights) {
      sum += l.intensity;
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(l.center[a], ref.grid.origin[a] - slack) << "level " << level.level;
        EXPECT_LE(l.center[a], ref.grid.boundsMax[a] + slack) << "level " << level.level;
        EXPECT_GE(l.variance[a], 0.0);
      }
      EXPECT_GT(l.luminance, 0.0);
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sum[c], total[c], 1.0e-9 * total[c]) << "level " << level.level;
    }
  }
  if (ref.levelCount > 0) EXPECT_LE(ref.levels.back().lights.size(), 8U);
}

TEST(LghCpuReference, SingleLightInsideACell) {
  // Lights at the corners of [0,4]^3 fix the grid (top 4, two levels: h1 = 2); the probe light at
  // (1, 0.5, 1.5) sits in S1 cell (0,0,0) with fractions (0.5, 0.25, 0.75).
  std::vector<PointLight> lights{light({0, 0, 0}, {1, 1, 1}), light({4, 4, 4}, {1, 1, 1}),
                                 light({1, 0.5F, 1.5F}, {2, 2, 2})};
  const LghReference ref = lgh::buildLghReference(lights, settings(2));
  ASSERT_EQ(ref.levelCount, 2);
  const auto& s1 = ref.levels[0];
  EXPECT_EQ(s1.dims, glm::uvec3(3));
  EXPECT_DOUBLE_EQ(s1.cellSize, 2.0);
  // Vertex (1,0,1) (index 1 + 9 = 10) gets w = 0.5 * 0.75 * 0.75 of the probe only.
  const auto* v = &s1.lights[0];
  for (const auto& l : s1.lights) {
    if (l.vertex == 10) v = &l;
  }
  ASSERT_EQ(v->vertex, 10U);
  EXPECT_NEAR(v->intensity.x, 2.0 * 0.5 * 0.75 * 0.75, 1e-12);
  EXPECT_NEAR(v->center.x, 1.0, 1e-12);
  EXPECT_NEAR(v->center.y, 0.5, 1e-12);
  EXPECT_NEAR(v->center.z, 1.5, 1e-12);
  EXPECT_NEAR(glm::length(v->variance), 0.0, 1e-12);
  expectInvariants(lights, ref);
}

TEST(LghCpuReference, TwoLightsCentreAndVariance) {
  // Two lights on the x axis of one S1 cell: intensities 1 and 3 (grey), x = 0.5 and 1.5 (h = 2);
  // two dim lights at (0,4,0) and (4,0,0) stretch the bounds to a 4 x 4 square at other vertices.
  std::vector<PointLight> lights{light({0, 4, 0}, {1e-3F, 0, 0}), light({0.5F, 0, 0}, {1, 1, 1}),
                                 light({1.5F, 0, 0}, {3, 3, 3}), light({4, 0, 0}, {1e-3F, 0, 0})};
  const LghReference ref = lgh::buildLghReference(lights, settings(2));
  const auto& s1 = ref.levels[0];
  // Vertex x=0: weights 0.75 and 0.25 -> w*I = 0.75 and 0.75; centre 1.0, variance 0.25.
  ASSERT_FALSE(s1.lights.empty());
  const auto& v0 = s1.lights[0];
  EXPECT_EQ(v0.vertex, 0U);
  EXPECT_NEAR(v0.intensity.y, 1.5, 1e-12);
  EXPECT_NEAR(v0.center.x, 1.0, 1e-12);
  EXPECT_NEAR(v0.variance.x, 0.25, 1e-12);
  EXPECT_NEAR(v0.variance.y, 0.0, 1e-12);
}

TEST(LghCpuReference, GatherAndScatterShareS1AndTotals) {
  const auto lights = lgh::uniformLights(3000, {-1, 0, -1}, {1, 2, 1}, 7);
  const LghReference gather = lgh::buildLghReference(lights, settings(5, Method::Gather));
  const LghReference scatter = lgh::buildLghReference(lights, settings(5, Method::Scatter));
  ASSERT_EQ(gather.levels[0].lights.size(), scatter.levels[0].lights.size());
  for (std::size_t i = 0; i < gather.levels[0].lights.size(); ++i) {
    EXPECT_EQ(gather.levels[0].lights[i].vertex, scatter.levels[0].lights[i].vertex);
    EXPECT_EQ(gather.levels[0].lights[i].center, scatter.levels[0].lights[i].center);
  }
  expectInvariants(lights, gather);
  expectInvariants(lights, scatter);
}

TEST(LghCpuReference, InvariantsOnStructuredInputs) {
  const std::vector<std::vector<PointLight>> sets{
      lgh::uniformLights(2000, {-3, -1, 2}, {5, 1, 2.5F}, 1),
      lgh::clusteredLights(2000, 5, 0.05F, {0, 0, 0}, {10, 10, 10}, 2),
      lgh::planeLights(1500, {0, 1, 0}, {2, 0, 0}, {0, 0, 3}, 3),
      lgh::latticeLights(9, {-2, -2, -2}, 0.5F, 4)};
  for (const auto& lights : sets) {
    for (Method method : {Method::Gather, Method::Scatter}) {
      expectInvariants(lights, lgh::buildLghReference(lights, settings(0, method)));
      expectInvariants(lights, lgh::buildLghReference(lights, settings(6, method)));
    }
  }
}

TEST(LghCpuReference, PlaneHasNoVarianceAcrossIt) {
  const auto lights = lgh::planeLights(1000, {0, 0.3F, 0}, {1, 0, 0}, {0, 0, 1}, 11);
  const LghReference ref = lgh::buildLghReference(lights, settings(4));
  for (const auto& level : ref.levels) {
    EXPECT_EQ(level.dims.y, 1U);
    for (const auto& l : level.lights) {
      EXPECT_NEAR(l.center.y, 0.3, 1e-6);
      EXPECT_NEAR(l.variance.y, 0.0, 1e-12);
    }
  }
}

TEST(LghCpuReference, AutoLevelsFollowThePaperRule) {
  for (int count : {100, 1000, 10000}) {
    const auto lights = lgh::sampleSurfaceVpls(lgh::makeDemoScene(), {count, 5, 1.0F});
    const LghReference ref = lgh::buildLghReference(lights, settings(0));
    const int L = ref.levelCount;
    ASSERT_GE(L, 1);
    ASSERT_EQ(ref.candidateS1.size(), static_cast<std::size_t>(ref.fitLevels));
    EXPECT_EQ(ref.candidateS1[L - 1], ref.levels[0].lights.size());
    if (L > 1) EXPECT_LT(2 * ref.levels[0].lights.size(), ref.contributingCount) << count;
    for (int larger = L + 1; larger <= ref.fitLevels; ++larger) {
      EXPECT_GE(2 * ref.candidateS1[larger - 1], ref.contributingCount) << count;
    }
  }
}

TEST(LghCpuReference, TopLevelIsOneCell) {
  const auto lights = lgh::uniformLights(500, {0, 0, 0}, {3, 1, 2}, 9);
  const LghReference ref = lgh::buildLghReference(lights, settings(5));
  EXPECT_EQ(ref.levels.back().dims, glm::uvec3(2));
  EXPECT_FLOAT_EQ(static_cast<float>(ref.levels.back().cellSize), ref.grid.top);
  EXPECT_NEAR(ref.levels[0].cellSize, ref.grid.top / 16.0, 1e-9);
}

TEST(LghCpuReference, EmptyAndDark) {
  EXPECT_EQ(lgh::buildLghReference({}, settings(0)).levelCount, 0);
  std::vector<PointLight> dark{light({1, 2, 3}, {0, 0, 0}), light({4, 5, 6}, {0, 0, 0})};
  const LghReference ref = lgh::buildLghReference(dark, settings(3));
  EXPECT_EQ(ref.levelCount, 0);
  EXPECT_EQ(ref.contributingCount, 0U);
}

TEST(LghCpuReference, OneLightAndOnePoint) {
  for (int count : {1, 50}) {
    std::vector<PointLight> lights(count, light({2.5F, -1, 7}, {0.5F, 0.25F, 1}));
    for (Method method : {Method::Gather, Method::Scatter}) {
      const LghReference ref = lgh::buildLghReference(lights, settings(count == 1 ? 0 : 4, method));
      ASSERT_GE(ref.levelCount, 1);
      EXPECT_GT(ref.grid.top, 0.0F);
      for (const auto& level : ref.levels) {
        ASSERT_EQ(level.lights.size(), 1U);
        EXPECT_NEAR(level.lights[0].center.x, 2.5, 1e-9);
        EXPECT_NEAR(level.lights[0].intensity.z, count * 1.0, 1e-9);
        EXPECT_NEAR(glm::length(level.lights[0].variance), 0.0, 1e-12);
      }
      expectInvariants(lights, ref);
    }
  }
}

TEST(LghCpuReference, ZeroIntensityLightsAreDropped) {
  auto lights = lgh::uniformLights(400, {0, 0, 0}, {1, 1, 1}, 3);
  for (std::size_t i = 0; i < lights.size(); i += 2) lights[i].intensityPad = glm::vec4(0.0F);
  lights.push_back(light({50, 50, 50}, {0, 0, 0}));  // dark lights do not stretch the grid
  const LghReference ref = lgh::buildLghReference(lights, settings(0));
  EXPECT_EQ(ref.contributingCount, 200U);
  EXPECT_LE(ref.grid.boundsMax.x, 1.0F);
  expectInvariants(lights, ref);
}

TEST(LghCpuReference, InvalidLightsAreRejected) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const PointLight& bad :
       {light({nan, 0, 0}, {1, 1, 1}), light({0, inf, 0}, {1, 1, 1}), light({0, 0, 0}, {1, nan, 1}),
        light({0, 0, 0}, {-1, 1, 1}), light({2e30F, 0, 0}, {1, 1, 1})}) {
    std::vector<PointLight> lights{light({0, 0, 0}, {1, 1, 1}), bad};
    try {
      lgh::buildLghReference(lights, settings(0));
      ADD_FAILURE() << "accepted an invalid light";
    } catch (const lgh::Error& error) {
      EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid);
    }
  }
}

TEST(LghCpuReference, BudgetCapsTheLevels) {
  const auto lights = lgh::uniformLights(1000, {0, 0, 0}, {1, 1, 1}, 2);
  LghBuildSettings s = settings(7);
  s.denseVertexBudget = 50'000;  // raised to hold a 7-level cube: 65^3 + 33^3 + ... vertices
  EXPECT_EQ(lgh::buildLghReference(lights, s).levelCount, 7);
  s.levels = 0;  // auto levels stay within the budget given
  EXPECT_LE(lgh::buildLghReference(lights, s).grid.denseTotal(
                lgh::buildLghReference(lights, s).levelCount),
            50'000U);
  EXPECT_EQ(lgh::lghResolveDenseBudget(1000, settings(12)), std::size_t{1} << 25);
  const auto grid = lgh::buildLghReference(lights, settings(1)).grid;
  EXPECT_EQ(grid.fitLevels(std::size_t{1} << 25), 9);  // 257^3 fits, 513^3 does not
  EXPECT_EQ(grid.fitLevels(50'000), 6);                // 4 x 1024 + 5120 + 36864 (33^3) vertices
}

TEST(VplSampler, DeterministicInsideTheSceneAndFluxPreserving) {
  const lgh::Scene scene = lgh::makeDemoScene();
  const auto a = lgh::sampleSurfaceVpls(scene, {2000, 42, 10.0F});
  const auto b = lgh::sampleSurfaceVpls(scene, {2000, 42, 10.0F});
  const auto c = lgh::sampleSurfaceVpls(scene, {2000, 43, 10.0F});
  ASSERT_EQ(a.size(), 2000U);
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(PointLight)));
  EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(PointLight)));
  const double slack = 1e-4;
  double luminance = 0.0;
  for (const PointLight& l : a) {
    EXPECT_TRUE(lgh::lghValidLight(l));
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(l.positionPad[k], scene.bounds.min[k] - slack);
      EXPECT_LE(l.positionPad[k], scene.bounds.max[k] + slack);
    }
    luminance += lgh::lghLuminance(glm::vec3(l.intensityPad));
  }
  // Albedos are below 1: the total luminance is a fraction of the flux.
  EXPECT_GT(luminance, 1.0);
  EXPECT_LT(luminance, 10.0);
}

TEST(VplSampler, AreaWeighted) {
  lgh::Scene scene;
  lgh::Mesh mesh;
  lgh::Primitive quad;
  for (glm::vec3 p :
       {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}) {
    lgh::Vertex v;
    v.position = p;
    quad.vertices.push_back(v);
  }
  quad.indices = {0, 1, 2, 0, 2, 3};
  mesh.primitives.push_back(quad);
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0F)});
  glm::mat4 scaled(1.0F);
  scaled[0][0] = 3.0F;                 // 3x the area
  scaled[3] = glm::vec4(10, 0, 0, 1);  // at x in [10, 13]
  scene.instances.push_back({0, scaled});
  const auto lights = lgh::sampleSurfaceVpls(scene, {40000, 1, 1.0F});
  int far = 0;
  for (const PointLight& l : lights) far += l.positionPad.x >= 10.0F ? 1 : 0;
  // Binomial(40000, 0.75): sigma = 86.6; allow 5 sigma.
  EXPECT_NEAR(far, 30000, 433);
}

TEST(VplSampler, NoSurfaceIsAnError) {
  EXPECT_TRUE(lgh::sampleSurfaceVpls(lgh::Scene{}, {0, 1, 1.0F}).empty());
  EXPECT_THROW(lgh::sampleSurfaceVpls(lgh::Scene{}, {10, 1, 1.0F}), lgh::Error);
}

}  // namespace
