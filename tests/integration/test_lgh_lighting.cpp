// LGH many-light lighting on Mesa llvmpipe, small: the demo room at 64x48 with 4000 VPLs. The
// room without the demo's row of illumination-model spheres (docs/MATERIALS.md): at 64x48 they
// are a few pixels wide, and the floor VPLs' near field around them and interleaving's tiles
// across them dominate the error figures below at this VPL count, seed by seed (docs/LIGHTING.md).
// Checks (metrics and thresholds documented in docs/LIGHTING.md):
//  - the raster and compute paths produce the same image (relative RMSE of the indirect images
//    <= 2e-3: fp16 storage and float summation order) and, where the raster path's fragments of a
//    pixel run in order (llvmpipe; interlock on GPUs), the same reservoirs (F within 1e-4
//    relative, >= 99% of the sample slots identical: both stream the lights in buffer order);
//  - the hierarchy's error against the brute force over the same VPLs (same clamp: the hierarchy
//    alone), per material class and as a brightness bias, falls as alpha grows (1 -> 2 -> 4) and
//    stays within bounds on the diffuse pixels (docs/GI.md, "Metrics");
//  - the brute force itself matches an independent CPU reference of the lighting (double
//    precision, the glTF BRDF written from the specification);
//  - interleaving's extra error is bounded (2x2, 4x4), and its images agree across paths;
//  - the GLSL reservoir chooses light i with probability f_i / sum f (chi-square, p > 1e-3) and
//    makes exactly the choices of its C++ mirror;
//  - the overdraw counter, the shadow samples, timing rows and recorded paths are there.
// Images go to <build>/test-output/lgh_*.png for a look.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <numeric>
#include <string>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "gl/shader_library.hpp"
#include "lgh/testing/cpu_lighting.hpp"
#include "lgh/testing/image_metrics.hpp"
#include "lgh/testing/reservoir.hpp"
#include "scene/demo_scene.hpp"
#include "scene/scene_cache.hpp"
#include "test_support.hpp"

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kVpls = 4000;
constexpr int kQualityVpls = 20000;          // 5 levels: the clamp h_1 is an eighth of the room
constexpr double kMaxPathDifference = 2e-3;  // relative RMSE, raster vs compute
constexpr double kMinPValue = 1e-3;
// Light leakage keeps the hierarchy brighter than the brute force (docs/GI.md, "Metrics").
constexpr double kMaxBiasAlpha2 = 0.06;
constexpr double kMaxBiasAlpha4 = 0.03;

struct Frame {
  lgh::FrameReport result;
  lgh::LghFrameProbe probe;
};

struct Options {
  std::string path = "compute";
  std::string interleave = "none";
  float alpha = 1.0F;
  int samples = 4;
  bool locked = false;
  bool sampleS1 = false;
  int vpls = kVpls;
  int frame = 0;
  float jitter = 0.0F;
};

// The demo scene less the row of model spheres: their meshes come last, named <model>_sphere.
lgh::Scene roomWithoutModelRow() {
  lgh::Scene scene = lgh::makeDemoScene();
  auto inRow = [&](int mesh) {
    const std::string& name = scene.meshes[static_cast<std::size_t>(mesh)].name;
    return name != "sphere" && name.ends_with("_sphere");
  };
  std::erase_if(scene.instances,
                [&](const lgh::MeshInstance& instance) { return inRow(instance.mesh); });
  while (!scene.meshes.empty() && inRow(static_cast<int>(scene.meshes.size()) - 1)) {
    scene.meshes.pop_back();
  }
  scene.computeBounds();
  return scene;
}

class LghLighting : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    room = std::make_shared<lgh::CachedScene>();
    room->scene = roomWithoutModelRow();
    room->gpu = std::make_unique<lgh::GpuScene>(room->scene, lgh::GpuSceneOptions{});
    pipeline = std::make_unique<lgh::FramePipeline>();
  }
  static void TearDownTestSuite() {
    pipeline.reset();
    room.reset();
    context.reset();
  }

  static lgh::RenderRequest request(const Options& o) {
    return lgh::parseRenderRequest(fmt::format(
        R"({{"output": {{"width": {}, "height": {}}},
            "settings": {{"lgh": {{"enabled": true, "vpl_count": {}, "seed": 7, "alpha": {},
              "path": "{}", "interleave": "{}", "shadow_samples": {}, "locked_reservoir": {},
              "sample_s1": {}, "frame": {}, "shadow_jitter": {}}}}}}})",
        kWidth, kHeight, o.vpls, o.alpha, o.path, o.interleave, o.samples, o.locked, o.sampleS1,
        o.frame, o.jitter));
  }

  static Frame render(const Options& options, bool bruteForce = false, bool overdraw = false) {
    Frame frame;
    frame.probe.bruteForce = bruteForce;
    frame.probe.overdraw = overdraw;
    const lgh::RenderRequest req = request(options);
    lgh::gl::GpuTimer timer;
    pipeline->render(req, *room, timer, frame.result, &frame.probe);
    return frame;
  }

  static void save(const lgh::FloatImage& image, const std::string& name) {
    const lgh::Image8 display = lgh::toDisplay8(image, lgh::ToneMap::Aces, 4.0F, false);
    lgh::image_io::writeFile(lgh::test::outputDir() / (name + ".png"),
                             lgh::image_io::encodePng(display));
  }

  static double rmseVsReference(const Frame& frame) {
    return lgh::compareToReference(frame.probe.indirect, frame.probe.reference).relativeRmse;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::shared_ptr<lgh::CachedScene> room;
  static inline std::unique_ptr<lgh::FramePipeline> pipeline;
};

double relativeDifference(const std::vector<float>& a, const std::vector<float>& b) {
  double difference = 0.0;
  double norm = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    difference += (a[i] - b[i]) * (a[i] - b[i]);
    norm += b[i] * b[i];
  }
  return norm > 0.0 ? std::sqrt(difference / norm) : std::sqrt(difference);
}

double identicalSampleFraction(const Frame& a, const Frame& b) {
  std::size_t same = 0;
  std::size_t used = 0;
  for (std::size_t i = 0; i < a.probe.shadowSamples.size(); ++i) {
    const glm::vec4 x = a.probe.shadowSamples[i];
    const glm::vec4 y = b.probe.shadowSamples[i];
    if (x.w == 0.0F && y.w == 0.0F) continue;
    ++used;
    if (glm::length(glm::vec3(x - y)) <= 1e-4F * (1.0F + glm::length(glm::vec3(y))) &&
        std::fabs(x.w - y.w) <= 1e-3F * y.w) {
      ++same;
    }
  }
  return used > 0 ? static_cast<double>(same) / static_cast<double>(used) : 0.0;
}

void expectPathsAgree(const Frame& raster, const Frame& compute, const std::string& label,
                      double minIdenticalSamples, double maxSumDifference) {
  const auto image = lgh::compareToReference(raster.probe.indirect, compute.probe.indirect);
  const double sums = relativeDifference(raster.probe.reservoirSums, compute.probe.reservoirSums);
  const double identical = identicalSampleFraction(raster, compute);
  std::cout << fmt::format(
      "[ lgh ] raster vs compute, {}: image relative RMSE {:.2e}, "
      "PSNR {:.1f} dB; F relative difference {:.2e}; identical samples {:.4f}\n",
      label, image.relativeRmse, image.psnr, sums, identical);
  EXPECT_LE(image.relativeRmse, kMaxPathDifference) << label;
  EXPECT_LE(sums, maxSumDifference) << label;
  EXPECT_GE(identical, minIdenticalSamples) << label;
}

TEST_F(LghLighting, RasterAndComputeAgree) {
  for (const char* interleave : {"none", "2x2", "4x4"}) {
    Options options;
    options.interleave = interleave;
    options.path = "raster";
    const Frame raster = render(options);
    options.path = "compute";
    const Frame compute = render(options);
    EXPECT_EQ(raster.result.decisions.at("lgh_lighting"), "raster");
    EXPECT_EQ(compute.result.decisions.at("lgh_lighting"), "compute");
    // llvmpipe shades the fragments of a pixel in primitive order: even unlocked, the raster
    // reservoir sees the lights in the compute path's order. A GPU shades fragments of one pixel
    // concurrently: unlocked, reservoir updates race and get lost (the paper's trade-off, strong
    // at this tiny size; docs/LIGHTING.md), so there only the images must agree.
    const bool ordered = context->info().softwareRenderer;
    expectPathsAgree(raster, compute, interleave, ordered ? 0.99 : 0.0, ordered ? 1e-4 : 1.0);
    save(raster.probe.indirect, std::string("lgh_raster_") + interleave);
    save(compute.probe.indirect, std::string("lgh_compute_") + interleave);
  }
}

TEST_F(LghLighting, LockedReservoirAgreesWithCompute) {
  Options options;
  options.locked = true;
  options.path = "raster";
  const Frame raster = render(options);
  options.path = "compute";
  const Frame compute = render(options);
  // Interlock and the spin lock both keep every update; interlock also keeps primitive order.
  const std::string lock = raster.result.decisions.at("lgh_reservoir_lock");
  std::cout << "[ lgh ] raster reservoir lock: " << lock << '\n';
  const bool ordered = lock == "interlock" || context->info().softwareRenderer;
  expectPathsAgree(raster, compute, "locked", ordered ? 0.99 : 0.0, 1e-4);
}

TEST_F(LghLighting, RoomIsTheDemoLessItsModelRow) {
  EXPECT_EQ(room->scene.instances.size() + 6, lgh::makeDemoScene().instances.size());
}

// The independent check of the LGH (docs/GI.md, "Metrics"): the glossy metal sphere (3% of the
// pixels) holds most of the squared error, and the diffuse surfaces are a little too bright from
// light leakage (grid lights merge VPLs of neighbouring surfaces into centres off those
// surfaces). So the error is bounded per material class, and the bias is measured, not the
// headline relative RMSE alone.
TEST_F(LghLighting, HierarchyErrorPerMaterialClassFallsAsAlphaGrows) {
  double previousDiffuse = 1e30;
  double previousBias = 1e30;
  for (float alpha : {1.0F, 2.0F, 4.0F}) {
    Options options;
    options.alpha = alpha;
    options.vpls = kQualityVpls;
    const Frame frame = render(options, true);
    const lgh::MaterialErrors error = lgh::compareByMaterial(
        frame.probe.indirect, frame.probe.reference, frame.probe.metallicRoughness);
    std::cout << fmt::format(
        "[ lgh ] alpha {}: relative RMSE {:.4f} (diffuse {:.4f}, glossy {:.4f} on {:.1f}% of "
        "pixels), bias {:+.4f} (diffuse {:+.4f}), {} levels\n",
        alpha, error.all.relativeRmse, error.diffuse.relativeRmse, error.glossy.relativeRmse,
        100.0 * error.glossyFraction, error.bias, error.diffuseBias, frame.probe.levels.levelCount);
    EXPECT_LT(error.diffuse.relativeRmse, previousDiffuse) << "alpha " << alpha;
    EXPECT_LT(std::fabs(error.bias), previousBias) << "alpha " << alpha;
    EXPECT_GT(error.glossyFraction, 0.01) << "the demo's metal sphere is in view";
    if (alpha == 2.0F) {
      EXPECT_LT(error.diffuse.relativeRmse, 0.08);
      EXPECT_LT(std::fabs(error.bias), kMaxBiasAlpha2);
    }
    if (alpha == 4.0F) {
      EXPECT_LT(error.diffuse.relativeRmse, 0.04);
      EXPECT_LT(std::fabs(error.bias), kMaxBiasAlpha4);
    }
    previousDiffuse = error.diffuse.relativeRmse;
    previousBias = std::fabs(error.bias);
    if (alpha == 1.0F) save(frame.probe.reference, "lgh_bruteforce");
    save(frame.probe.indirect, fmt::format("lgh_alpha{}", alpha));
  }
}

// The brute force (every VPL at every pixel, the shading function the LGH's paths share) against
// the CPU reference, in double precision, at every fourth covered pixel, from the G-buffer and the
// VPLs the GPU used. A clamp of its own (0.05) so that the CPU knows it without the level table.
TEST_F(LghLighting, BruteForceMatchesAnIndependentCpuReference) {
  constexpr float kClamp = 0.05F;
  Options options;
  options.vpls = 600;
  Frame frame;
  frame.probe.bruteForce = true;
  frame.probe.readGBuffer = true;
  frame.probe.readVpls = true;
  frame.probe.referenceClamp = lgh::LghFrameProbe::ReferenceClamp::Fixed;
  frame.probe.referenceMinDistance = kClamp;
  const lgh::RenderRequest req = request(options);
  lgh::gl::GpuTimer timer;
  pipeline->render(req, *room, timer, frame.result, &frame.probe);
  const auto& g = frame.probe.gbuffer;
  ASSERT_EQ(frame.probe.vpls.size(), 600U);
  double worst = 0.0;
  double sum = 0.0;
  int compared = 0;
  for (std::size_t p = 0; p < g.position.size(); p += 4) {
    if (g.position[p].w < 0.5F) continue;
    lgh::CpuSurface surface;
    surface.position = glm::dvec3(glm::vec3(g.position[p]));
    surface.normal = glm::normalize(glm::dvec3(g.normal[p]));
    surface.baseColor = glm::dvec3(g.baseColor[p]);
    surface.metallic = frame.probe.metallicRoughness[p].x;
    surface.roughness = frame.probe.metallicRoughness[p].y;
    const glm::dvec3 cpu = lgh::cpuPointLightRadiance(surface, glm::dvec3(g.cameraPosition),
                                                      frame.probe.vpls, double{kClamp} * kClamp);
    const float* gpu = &frame.probe.reference.rgba[p * 4];
    for (int c = 0; c < 3; ++c) {
      const double difference = std::fabs(gpu[c] - cpu[c]) / std::max(cpu[c], 1e-3);
      worst = std::max(worst, difference);
      sum += difference;
    }
    ++compared;
  }
  std::cout << fmt::format(
      "[ lgh ] brute force vs CPU reference over {} pixels: relative "
      "difference mean {:.2e}, max {:.2e}\n",
      compared, sum / (3.0 * compared), worst);
  // llvmpipe decodes the sRGB base colour with an approximation good to about 1e-3 (relative;
  // white 0.7991 reads 0.7981): differences of that size come from the texture unit. A shading
  // error shows far above it (a dielectric F0 of 0.08 instead of 0.04: 4% on every wall).
  ASSERT_GT(compared, 500);
  EXPECT_LT(sum / (3.0 * compared), 3e-3);
  EXPECT_LT(worst, 1e-2);
}

TEST_F(LghLighting, InterleavedErrorIsBounded) {
  std::vector<double> errors;
  for (const char* interleave : {"none", "2x2", "4x4"}) {
    Options options;
    options.interleave = interleave;
    const Frame frame = render(options, true);
    errors.push_back(rmseVsReference(frame));
    std::cout << fmt::format("[ lgh ] interleave {}: relative RMSE vs brute force {:.4f}\n",
                             interleave, errors.back());
  }
  // The compositing smooths: some error on top of the hierarchy's, never a different image.
  EXPECT_LE(errors[1], errors[0] + 0.05);
  EXPECT_LE(errors[2], errors[0] + 0.10);
}

TEST_F(LghLighting, GpuReservoirMatchesMirrorAndWeights) {
  const std::vector<float> weights{0.5F, 1.0F, 2.0F, 3.0F, 0.0F, 4.0F, 8.0F, 0.25F, 1.5F, 6.0F};
  constexpr GLuint kPixels = 20000;
  constexpr int kSamples = 4;
  constexpr std::uint32_t kSeed = 99;
  lgh::gl::Program program = lgh::gl::buildComputeProgram("lgh_reservoir_test.comp");
  lgh::gl::Buffer weightBuffer;
  glNamedBufferStorage(weightBuffer.id(), static_cast<GLsizeiptr>(weights.size() * sizeof(float)),
                       weights.data(), 0);
  lgh::gl::Buffer choiceBuffer;
  std::vector<std::uint32_t> choices(std::size_t{kPixels} * kSamples);
  glNamedBufferStorage(choiceBuffer.id(), static_cast<GLsizeiptr>(choices.size() * 4), nullptr, 0);
  glUseProgram(program.id());
  glUniform1ui(glGetUniformLocation(program.id(), "uPixels"), kPixels);
  glUniform1ui(glGetUniformLocation(program.id(), "uLightCount"),
               static_cast<GLuint>(weights.size()));
  glUniform1i(glGetUniformLocation(program.id(), "uSampleCount"), kSamples);
  glUniform1ui(glGetUniformLocation(program.id(), "uSeed"), kSeed);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, weightBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, choiceBuffer.id());
  glDispatchCompute((kPixels + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(choiceBuffer.id(), 0, static_cast<GLsizeiptr>(choices.size() * 4),
                          choices.data());
  glUseProgram(0);

  std::size_t mirrorMatches = 0;
  std::vector<double> counts(weights.size(), 0.0);
  for (GLuint pixel = 0; pixel < kPixels; ++pixel) {
    lgh::reservoir::Reservoir mirror;
    const std::uint32_t seed = lgh::reservoir::pixelSeed(kSeed, pixel);
    for (std::uint32_t i = 0; i < weights.size(); ++i) mirror.add(seed, i, weights[i], kSamples);
    for (int s = 0; s < kSamples; ++s) {
      const std::uint32_t chosen = choices[pixel * kSamples + static_cast<GLuint>(s)];
      ASSERT_LT(chosen, weights.size());
      ASSERT_GT(weights[chosen], 0.0F);
      counts[chosen] += 1.0;
      if (chosen == mirror.light[static_cast<std::size_t>(s)]) ++mirrorMatches;
    }
  }
  EXPECT_EQ(mirrorMatches, choices.size()) << "the GLSL reservoir differs from its C++ mirror";
  const double sum = std::accumulate(weights.begin(), weights.end(), 0.0);
  double statistic = 0.0;
  int categories = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    if (weights[i] <= 0.0F) continue;
    const double expected = static_cast<double>(choices.size()) * weights[i] / sum;
    statistic += (counts[i] - expected) * (counts[i] - expected) / expected;
    ++categories;
  }
  // Chi-square survival function for dof = 8 (even: closed form).
  const double half = 0.5 * statistic;
  double term = 1.0;
  double series = 1.0;
  for (int j = 1; j < (categories - 1) / 2; ++j) {
    term *= half / j;
    series += term;
  }
  const double p = std::exp(-half) * series;
  ASSERT_EQ(categories - 1, 8);
  std::cout << fmt::format("[ lgh ] GPU reservoir chi-square {:.2f} (dof 8), p-value {:.4f}\n",
                           statistic, p);
  EXPECT_GT(p, kMinPValue);
}

TEST_F(LghLighting, OverdrawCounterImage) {
  for (const char* path : {"raster", "compute"}) {
    Options options;
    options.path = path;
    const Frame frame = render(options, false, true);
    const auto& counts = frame.probe.overdrawCounts;
    ASSERT_EQ(counts.size(), static_cast<std::size_t>(kWidth * kHeight));
    const double mean = std::accumulate(counts.begin(), counts.end(), 0.0) / counts.size();
    const std::uint32_t max = *std::max_element(counts.begin(), counts.end());
    std::cout << fmt::format("[ lgh ] overdraw {}: mean {:.1f}, max {}\n", path, mean, max);
    EXPECT_GT(mean, 1.0);
    EXPECT_GE(static_cast<double>(max), mean);
  }
}

TEST_F(LghLighting, ShadowSamplesAreValidAndSkipS1ByDefault) {
  Options options;
  const Frame skip = render(options);
  options.sampleS1 = true;
  const Frame withS1 = render(options);
  const int k = skip.probe.shadowSampleCount;
  ASSERT_EQ(k, 4);
  std::size_t sampledPixels = 0;
  std::size_t moreWithS1 = 0;
  for (std::size_t p = 0; p < skip.probe.reservoirSums.size(); ++p) {
    const float sum = skip.probe.reservoirSums[p];
    if (withS1.probe.reservoirSums[p] > sum * 1.0001F) ++moreWithS1;
    if (sum <= 0.0F) continue;
    ++sampledPixels;
    for (int s = 0; s < k; ++s) {
      const glm::vec4 sample = skip.probe.shadowSamples[p * k + static_cast<std::size_t>(s)];
      ASSERT_TRUE(std::isfinite(sample.x) && std::isfinite(sample.y) && std::isfinite(sample.z));
      ASSERT_GT(sample.w, 0.0F) << "pixel " << p << " sample " << s;
      // The demo room spans [-1, 1] x [0, 2] x [-1, 1]; jitter stays near it.
      ASSERT_LT(glm::length(glm::vec3(sample) - glm::vec3(0.0F, 1.0F, 0.0F)), 3.0F);
    }
  }
  EXPECT_GT(sampledPixels, skip.probe.reservoirSums.size() / 2);
  EXPECT_GT(moreWithS1, sampledPixels / 2) << "sampling S1 should add to F";
}

// Frames that are averaged need their own shadow samples: settings.lgh.frame gives each frame its
// own sequence (frame 0 is the seed's own), while the lighting itself does not change. The build's
// float atomics (llvmpipe has them) sum in a different order each run, so two runs differ by float
// rounding (about 3e-5 relative here) and a reservoir choice on a tie may flip: the bounds allow
// that and nothing more.
TEST_F(LghLighting, EachFrameIndexHasItsOwnShadowSamples) {
  Options options;
  options.jitter = 1.0F;  // the jitter draws from the sequence too
  const Frame first = render(options);
  const Frame again = render(options);
  options.frame = 1;
  const Frame next = render(options);
  EXPECT_GE(identicalSampleFraction(first, again), 0.99);
  EXPECT_LT(identicalSampleFraction(first, next), 0.5) << "frame 1 draws other samples";
  EXPECT_LT(lgh::compareToReference(next.probe.indirect, first.probe.indirect).relativeRmse, 1e-4)
      << "the lighting does not depend on the frame";
}

TEST_F(LghLighting, RecordsTimingsAndPaths) {
  Options options;
  options.path = "raster";
  options.interleave = "2x2";
  const Frame raster = render(options);
  for (const char* pass : {"lgh build", "lgh bounds", "lgh interleave split", "lgh lighting",
                           "lgh interleave composite", "composite"}) {
    EXPECT_GE(raster.result.timings.get(pass), 0.0) << pass;
  }
  EXPECT_EQ(raster.result.decisions.at("lgh_lighting_choice"), "configured");
  EXPECT_EQ(raster.result.decisions.at("interleave"), "2x2");
  options.path = "auto";
  const Frame automatic = render(options, true);
  if (context->info().softwareRenderer) {
    EXPECT_EQ(automatic.result.decisions.at("lgh_lighting"), "compute");
    EXPECT_EQ(automatic.result.decisions.at("lgh_lighting_choice"), "rule");
  } else {
    EXPECT_EQ(automatic.result.decisions.at("lgh_lighting_choice"), "measured");
  }
  EXPECT_EQ(automatic.result.decisions.at("reference"), "brute-force");
}

TEST_F(LghLighting, NoVplsMeansNoIndirectLight) {
  Options options;
  options.vpls = 0;
  const Frame frame = render(options);
  EXPECT_EQ(frame.result.decisions.at("lgh_lighting"), "none");
  EXPECT_FALSE(frame.result.warnings.empty());
}

}  // namespace
