#include "frame_pipeline.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "core/stopwatch.hpp"
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

FramePipeline::FramePipeline(ShadowDevice* shadowDevice) : shadows_(shadowDevice) {}
FramePipeline::~FramePipeline() = default;

void FramePipeline::render(const RenderRequest& request, const CachedScene& cached,
                           gl::GpuTimer& timer, FrameReport& report, LghFrameProbe* probe) {
  const OutputSettings& output = request.output;
  const CameraMatrices camera =
      computeCamera(request.camera, cached.scene, output.width, output.height);
  const std::vector<LightDesc> lights = frameLights(request, cached.scene, camera, report.warnings);
  const LghSettings& lgh = request.settings.lgh;
  const ShadowSettings& shadowSettings = request.settings.shadows;
  // The scene's materials with the request's parameters (docs/MATERIALS.md), for this frame.
  const MaterialTable materials(cached.scene, request.materials);
  targets_.resize(output.width, output.height);
  uploadLights(lights, lightBuffer_);
  const auto lightCount = static_cast<int>(lights.size());
  {
    gl::ScopedGpuPass pass(timer, "gbuffer");
    gbufferPass_.run(
        {&materials, &camera, &request.settings.primitives, lightBuffer_.id(), lightCount},
        *cached.gpu, targets_);
  }
  LghFrameLighting::ShadowSamples samples;
  if (lgh.enabled) {
    if (!lghLighting_) lghLighting_ = std::make_unique<LghFrameLighting>();
    lghLighting_->run(lgh, cached, camera, targets_, timer, report, probe);
    samples = lghLighting_->shadowSamples();
  }
  shadows_.trace(
      {shadowSettings, lgh.seed, lightBuffer_.id(), lightCount, samples.buffer, samples.count},
      cached, targets_, timer, report);
  {
    gl::ScopedGpuPass pass(timer, "direct lighting");
    directLightingPass_.run({lightBuffer_.id(), lightCount, shadows_.layout(),
                             shadows_.visibility(), request.settings.ambient},
                            camera, targets_);
  }
  const GLuint shadowRatio =
      shadows_.filterLgh(shadowSettings.filterIterations, camera, targets_, timer);
  {
    gl::ScopedGpuPass pass(timer, "composite");
    compositePass_.run(output, lgh.enabled, shadowRatio, targets_);
  }
  if (ForwardBlendPass::needed(materials, *cached.gpu)) {
    gl::ScopedGpuPass pass(timer, "forward blend");
    const int blended = forwardBlendPass_.run(
        {&materials, &camera, &request.settings.primitives, lightBuffer_.id(), lightCount,
         request.settings.ambient, gbufferPass_.maxTessellationLevel()},
        gbufferPass_.programs(), *cached.gpu, targets_);
    report.decide("blended_surfaces", std::to_string(blended));
  }
  const Stopwatch readback;
  report.image = readbackFinal(targets_);
  const double readbackMs = readback.elapsedMs();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  timer.collect(report.timings);
  shadows_.collectTimings(report);
  report.timings.add("readback", TimingRow::Clock::Cpu, readbackMs);
  report.decide("lighting", lgh.enabled ? "direct+lgh" : "direct");
  report.decide("lights", std::to_string(lights.size()));
  report.decide("texture_memory", textureMemoryText(cached.gpu->textureMemory()));
  // What unset `sampling.anisotropy` gets, and where a request's value is capped.
  report.decide("texture_anisotropy", fmt::format("{:g}", cached.gpu->maxAnisotropy()));
  for (std::string& warning : cached.gpu->takeWarnings()) {
    report.warnings.push_back(std::move(warning));
  }
}

}  // namespace lgh
