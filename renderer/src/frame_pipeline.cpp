#include "frame_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "core/stopwatch.hpp"
#include "lgh/error.hpp"
#include "passes/brdf_features.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "passes/light_buffer.hpp"
#include "scene/material_table.hpp"

namespace lgh {
namespace {

LightDesc directionalLight(const glm::vec3& direction, float intensity) {
  LightDesc light;
  light.type = LightType::Directional;
  const glm::vec3 d = glm::normalize(direction);
  light.direction = {d.x, d.y, d.z};
  light.intensity = intensity;
  return light;
}

// What the scene's textures take on the GPU, and what block compression saved.
std::string textureMemoryText(const GpuScene::TextureMemory& memory) {
  constexpr double kMiB = 1024.0 * 1024.0;
  auto mib = [](std::size_t bytes) { return static_cast<double>(bytes) / kMiB; };
  std::string text = fmt::format("{:.2f} MiB in {} textures", mib(memory.bytes), memory.textures);
  if (memory.compressed > 0) {
    const std::size_t saved =
        memory.uncompressedBytes - std::min(memory.bytes, memory.uncompressedBytes);
    text += fmt::format(" ({} block-compressed; {:.2f} MiB as RGBA8, saved {:.2f} MiB)",
                        memory.compressed, mib(memory.uncompressedBytes), mib(saved));
  }
  return text;
}

}  // namespace

std::vector<LightDesc> frameLights(const RenderRequest& request, const Scene& scene,
                                   const CameraMatrices& camera,
                                   std::vector<std::string>& warnings) {
  std::vector<LightDesc> lights = scene.lights;
  lights.insert(lights.end(), request.lights.begin(), request.lights.end());
  if (!lights.empty() || !request.useDemoLightsWhenNone) return lights;
  // A key light from above the camera's left shoulder and a dimmer fill from the right.
  const glm::mat4 cameraToWorld = glm::inverse(camera.view);
  const glm::vec3 right(cameraToWorld[0]);
  const glm::vec3 up(cameraToWorld[1]);
  const glm::vec3 forward = -glm::vec3(cameraToWorld[2]);
  lights.push_back(directionalLight(forward - up * 0.8F + right * 0.5F, 2.5F));
  lights.push_back(directionalLight(forward + up * 0.2F - right * 0.8F, 0.8F));
  warnings.emplace_back("the scene has no lights: added a default key and fill light");
  return lights;
}

FramePipeline::FramePipeline(ShadowDevice* shadowDevice)
    : sets_{std::make_unique<FrameSet>(shadowDevice, 0),
            std::make_unique<FrameSet>(shadowDevice, 1)},
      targets_(sets_[0]->targets),
      shadows_(sets_[0]->shadows),
      gi_(shadowDevice) {}
FramePipeline::~FramePipeline() = default;

FramePipeline::FrameSet& FramePipeline::frameSet(int set) {
  if (set < 0 || set >= kFrameSets) {
    throw Error(ErrorCode::Internal, fmt::format("frame set {} of {}", set, kFrameSets));
  }
  return *sets_[static_cast<std::size_t>(set)];
}

void FramePipeline::draw(const RenderRequest& request, const CachedScene& cached,
                         gl::GpuTimer& timer, FrameReport& report, OutputPixels pixels,
                         LghFrameProbe* probe) {
  drawInto(*sets_[0], request, cached, timer, report, pixels, false, probe);
}

std::optional<RemainingPasses> FramePipeline::drawUntilShadows(const RenderRequest& request,
                                                               const CachedScene& cached,
                                                               gl::GpuTimer& timer,
                                                               FrameReport& report,
                                                               OutputPixels pixels, int set) {
  std::optional<RemainingPasses> remaining =
      drawInto(frameSet(set), request, cached, timer, report, pixels, true, nullptr);
  if (remaining) remaining->set = set;
  return remaining;
}

void FramePipeline::finishDraw(const RemainingPasses& remaining, gl::GpuTimer& timer) {
  // A split frame has no LGH lighting and no blended surfaces: nothing to composite.
  directLighting(frameSet(remaining.set), remaining, timer, true);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glFlush();
}

void FramePipeline::directLighting(FrameSet& set, const RemainingPasses& remaining,
                                   gl::GpuTimer& timer, bool toOutput) {
  set.shadows.awaitVisibility();
  gl::ScopedGpuPass pass(timer, "direct lighting", gl::GpuWork::Compute);
  const DirectLightingInputs inputs{
      set.lightBuffer.id(), remaining.lightCount, set.shadows.layout(), set.shadows.visibility(),
      remaining.ambient,    remaining.brdf,       remaining.emission};
  if (toOutput) {
    directLightingPass_.runToOutput(inputs, remaining.camera, remaining.output, remaining.pixels,
                                    set.targets);
  } else {
    directLightingPass_.run(inputs, remaining.camera, set.targets);
  }
}

std::optional<RemainingPasses> FramePipeline::drawInto(FrameSet& set, const RenderRequest& request,
                                                       const CachedScene& cached,
                                                       gl::GpuTimer& timer, FrameReport& report,
                                                       OutputPixels pixels, bool maySplit,
                                                       LghFrameProbe* probe) {
  const Stopwatch setup;
  const OutputSettings& output = request.output;
  RemainingPasses remaining;
  remaining.camera = computeCamera(request.camera, cached.scene, output.width, output.height);
  const CameraMatrices& camera = remaining.camera;
  const std::vector<LightDesc> lights = frameLights(request, cached.scene, camera, report.warnings);
  const LghSettings& lgh = request.settings.lgh;
  const ShadowSettings& shadowSettings = request.settings.shadows;
  // The scene's materials with the request's parameters (docs/MATERIALS.md), for this frame.
  const MaterialTable materials(cached.scene, request.materials);
  FrameTargets& targets = set.targets;
  targets.resize(output.width, output.height);
  uploadLights(lights, set.lightBuffer);
  remaining.lightCount = static_cast<int>(lights.size());
  remaining.ambient = request.settings.ambient;
  remaining.output = output;
  remaining.pixels = pixels;
  const int lightCount = remaining.lightCount;
  // The models and layers the G-buffer holds: what the lighting kernels are compiled for.
  remaining.brdf = brdfFeatures(materials, cached.gpu->drawItems());
  remaining.emission = surfacesEmit(materials, cached.gpu->drawItems());
  const BrdfFeatures& brdf = remaining.brdf;
  // The render thread's work before the first pass: part of "submit", beside the passes' cpu_ms.
  report.timings.add("frame setup", TimingRow::Clock::Cpu, setup.elapsedMs());
  {
    gl::ScopedGpuPass pass(timer, "gbuffer");
    gbufferPass_.run({.materials = &materials,
                      .camera = &camera,
                      .primitives = &request.settings.primitives,
                      .lights = set.lightBuffer.id(),
                      .lightCount = lightCount,
                      .depthPrepass = request.settings.depthPrepass,
                      .writeLayers = brdf.usesLayersTarget(),
                      .writeEmissive = remaining.emission,
                      .clearEveryTarget = probe != nullptr,
                      .sceneBounds = &cached.scene.bounds},
                     *cached.gpu, targets);
  }
  LghFrameLighting::ShadowSamples samples;
  if (lgh.enabled) {
    if (!lghLighting_) lghLighting_ = std::make_unique<LghFrameLighting>();
    if (probe != nullptr) prepareProbe(request, cached, *probe);
    const LghGiInputs gi{request.settings.gi,    lights, set.lightBuffer.id(),
                         shadowSettings.tracing, gi_,    materials.materials()};
    lghLighting_->run(lgh, cached, camera, brdf, targets, timer, report, probe, &gi);
    if (probe != nullptr) probe->visibility = nullptr;  // it refers to this frame's scene
    samples = lghLighting_->shadowSamples();
  }
  ShadowFrame& shadows = set.shadows;
  shadows.trace({shadowSettings, samplingSeed(lgh), set.lightBuffer.id(), lightCount,
                 samples.buffer, samples.count},
                cached, targets, timer, report);
  const bool blends = ForwardBlendPass::needed(materials, *cached.gpu);
  // Rows timed by Vulkan, the light paths' then the shadow rays', read when the frame is taken.
  if (lghLighting_) lghLighting_->collectTimings(report);
  shadows.collectTimings(report);
  report.decide("lighting", lgh.enabled ? "direct+lgh" : "direct");
  report.decide("lights", std::to_string(lights.size()));
  reportScene(cached, report);
  const bool split = maySplit && shadows.traced() && !lgh.enabled && !blends &&
                     static_cast<long>(output.width) * output.height <= kMaxSplitPixels;
  report.decide("frame_overlap", split ? "split" : "whole");
  if (split) {
    glFlush();  // the G-buffer and the rays' set-up start while the CPU goes on
    return remaining;
  }
  // Direct lighting alone, unblended: its pass writes the output, and there is no composite.
  const bool composites = lgh.enabled || blends || probe != nullptr;
  directLighting(set, remaining, timer, !composites);
  if (!composites) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFlush();  // the GPU starts on the frame while the CPU goes on
    return std::nullopt;
  }
  const GLuint shadowRatio =
      shadows.filterLgh(shadowSettings.filterIterations, camera, targets, timer);
  if (probe != nullptr && lgh.enabled) finishProbe(shadowRatio, camera, *probe);
  if (!blends) {
    gl::ScopedGpuPass pass(timer, "composite", gl::GpuWork::Compute);
    compositePass_.run(output, pixels, lgh.enabled, shadowRatio, targets);
  } else {
    // Blending happens in linear light: composite into the scene target, blend the surfaces over
    // it, then the display pass writes what is read back.
    {
      gl::ScopedGpuPass pass(timer, "composite", gl::GpuWork::Compute);
      compositePass_.runToScene(output, lgh.enabled, shadowRatio, targets);
    }
    {
      gl::ScopedGpuPass pass(timer, "forward blend");
      const int blended = forwardBlendPass_.run(
          {&materials, &camera, &request.settings.primitives, set.lightBuffer.id(), lightCount,
           request.settings.ambient, gbufferPass_.maxTessellationLevel()},
          gbufferPass_.programs(), *cached.gpu, targets);
      report.decide("blended_surfaces", std::to_string(blended));
    }
    gl::ScopedGpuPass pass(timer, "display");
    displayPass_.run(output, pixels, targets);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glFlush();  // the GPU starts on the frame while the CPU goes on
  return std::nullopt;
}

void FramePipeline::reportScene(const CachedScene& cached, FrameReport& report) {
  report.decide("texture_memory", textureMemoryText(cached.gpu->textureMemory()));
  // What unset `sampling.anisotropy` gets, and where a request's value is capped.
  report.decide("texture_anisotropy", fmt::format("{:g}", cached.gpu->maxAnisotropy()));
  for (std::string& warning : cached.gpu->takeWarnings()) {
    report.warnings.push_back(std::move(warning));
  }
}

void FramePipeline::prepareProbe(const RenderRequest& request, const CachedScene& cached,
                                 LghFrameProbe& probe) {
  if (!probe.bruteForce || !probe.shadowedReference) return;
  const ShadowSettings settings = request.settings.shadows;
  probe.visibility = [this, settings, &cached](GLuint lights, int first, int count) {
    return shadows_.traceToPointLights(settings, lights, first, count, cached, targets_);
  };
}

namespace {

// A texture's texels as floats, top row first (GL's rows run bottom-up).
template <typename Texel>
std::vector<Texel> readTopDown(GLuint texture, int width, int height, GLenum format, int channels,
                               const auto& convert) {
  std::vector<float> raw(static_cast<std::size_t>(width) * height * channels);
  glGetTextureImage(texture, 0, format, GL_FLOAT, static_cast<GLsizei>(raw.size() * sizeof(float)),
                    raw.data());
  std::vector<Texel> texels(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      texels[static_cast<std::size_t>(height - 1 - y) * width + x] =
          convert(&raw[(static_cast<std::size_t>(y) * width + x) * channels]);
    }
  }
  return texels;
}

float srgbToLinear(float c) {
  return c <= 0.04045F ? c / 12.92F : std::pow((c + 0.055F) / 1.055F, 2.4F);
}

}  // namespace

void FramePipeline::finishProbe(GLuint shadowRatio, const CameraMatrices& camera,
                                LghFrameProbe& probe) const {
  if (!probe.readBack) return;
  if (probe.readGBuffer) {
    const GBufferTargets& g = targets_.gbuffer;
    const int w = targets_.width;
    const int h = targets_.height;
    probe.gbuffer.position =
        readTopDown<glm::vec4>(g.position.id(), w, h, GL_RGBA, 4,
                               [](const float* v) { return glm::vec4(v[0], v[1], v[2], v[3]); });
    probe.gbuffer.normal = readTopDown<glm::vec3>(
        g.normal.id(), w, h, GL_RGB, 3, [](const float* v) { return glm::vec3(v[0], v[1], v[2]); });
    // The sRGB target's bytes as stored; the lighting passes sample them decoded.
    probe.gbuffer.baseColor =
        readTopDown<glm::vec3>(g.albedo.id(), w, h, GL_RGB, 3, [](const float* v) {
          return glm::vec3(srgbToLinear(v[0]), srgbToLinear(v[1]), srgbToLinear(v[2]));
        });
    probe.gbuffer.cameraPosition = camera.position;
  }
  const int width = targets_.width;
  const int height = targets_.height;
  probe.shadowRatio = FloatImage{};
  probe.shadowRatio.width = width;
  probe.shadowRatio.height = height;
  probe.shadowRatio.rgba.assign(static_cast<std::size_t>(width) * height * 4, 1.0F);
  if (shadowRatio != 0) {
    std::vector<float> ratio(static_cast<std::size_t>(width) * height);
    glGetTextureImage(shadowRatio, 0, GL_RED, GL_FLOAT,
                      static_cast<GLsizei>(ratio.size() * sizeof(float)), ratio.data());
    for (int y = 0; y < height; ++y) {  // GL rows run bottom-up, images top-down
      for (int x = 0; x < width; ++x) {
        float* pixel =
            &probe.shadowRatio.rgba[(static_cast<std::size_t>(height - 1 - y) * width + x) * 4];
        pixel[0] = pixel[1] = pixel[2] = ratio[static_cast<std::size_t>(y) * width + x];
      }
    }
  }
  std::vector<std::uint8_t> material(static_cast<std::size_t>(width) * height * 4);
  glGetTextureImage(targets_.gbuffer.material.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                    static_cast<GLsizei>(material.size()), material.data());
  probe.metallicRoughness.resize(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* m = &material[(static_cast<std::size_t>(y) * width + x) * 4];
      probe.metallicRoughness[static_cast<std::size_t>(height - 1 - y) * width + x] =
          glm::vec2(m[0] / 255.0F, m[1] / 255.0F);
    }
  }
}

void FramePipeline::pack(OutputPixels pixels, FramePixels::Layout layout, GLuint packBuffer,
                         gl::GpuTimer& timer, int set) {
  gl::ScopedGpuPass pass(timer, "readback", gl::GpuWork::Compute);
  pixelPackPass_.run(frameSet(set).targets, pixels, layout, packBuffer);
}

void FramePipeline::render(const RenderRequest& request, const CachedScene& cached,
                           gl::GpuTimer& timer, FrameReport& report, LghFrameProbe* probe) {
  draw(request, cached, timer, report, OutputPixels::LinearFloat, probe);
  const Stopwatch readback;
  report.image = readLinearOutput(targets_);
  const double readbackMs = readback.elapsedMs();
  timer.collect(report.timings);
  report.timings.appendMerged(report.writeLateRows());
  report.timings.add("readback", TimingRow::Clock::Cpu, readbackMs);
}

}  // namespace lgh
