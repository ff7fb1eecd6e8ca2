// The light paths on Vulkan (shadow_tracer.hpp, "Light paths"): GI's VPL generation recorded
// into one command buffer and submitted once per frame,
//   upload the frame's sources and lights, clear the left-over VPL slots, gi_emit
//   per bounce:  barrier -> closest-hit trace (the HitTracer's recorder) -> barrier -> gi_bounce
// with timestamps between the steps. The rays, hits and paths stay in device-local buffers of
// its own; only the VPL buffer is shared with GL, acquired from and released to GL (interop) or
// read back by the host (staging) around the whole submission. VulkanShadowTracer owns one.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>

#include "vk/device_buffer.hpp"
#include "vk/exported_semaphores.hpp"
#include "vk/light_path_surfaces.hpp"
#include "vk/shadow_tracer.hpp"
#include "vk/trace_layout.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class AccelerationScene;
class HitTracer;
class TraceRecorder;
class VulkanDevice;

class LightPathTracer {
 public:
  // `hits`: whose recorders trace the bounces; `traceStages`: the stages of its tracing paths.
  LightPathTracer(const VulkanDevice& device, const HitTracer& hits,
                  ::vk::ShaderStageFlags traceStages);

  const VplBuffers& buffers(std::uint32_t vplCount, Transport transport);
  SemaphoreFds exportSemaphores();
  void trace(const AccelerationScene& scene, TracePath path, const LightPathScene& surfaces,
             const LightPathBatch& batch, bool useSemaphores);
  // The number of the last submission (0: none yet).
  std::uint64_t lastSubmission() const { return submitted_; }
  // The timings of submissions up to and including number `through` that no earlier call
  // returned, summed; waits for the one in flight only when it is one of them.
  LightPathTimings collectTimings(std::uint64_t through);
  // Banked timings kept for frames that never ask: beyond this, the oldest go.
  static constexpr std::size_t kMaxBanked = 64;

 private:
  // The buffers that never leave Vulkan: rays and hits (the trace's), the paths' state, and the
  // frame's inputs with their staging copy.
  struct Working {
    std::uint32_t paths = 0;
    DeviceBuffer rays;
    DeviceBuffer hits;
    DeviceBuffer states;
  };
  struct Inputs {
    ::vk::DeviceSize sourceBytes = 0;
    ::vk::DeviceSize lightBytes = 0;
    DeviceBuffer staging;
    DeviceBuffer sources;
    DeviceBuffer lights;
  };

  void check(const LightPathBatch& batch, bool useSemaphores) const;
  void prepare(const LightPathScene& surfaces, const LightPathBatch& batch);
  void writeSets(const AccelerationScene& scene) const;
  void record(const TraceRecorder& recorder, const LightPathBatch& batch) const;
  void submit(bool useSemaphores);
  // Waits for the submission in flight, if any, and banks its timings under its number.
  void retire();

  const VulkanDevice* device_;
  const HitTracer* hits_;
  ::vk::raii::DescriptorSetLayout setLayout_;
  ::vk::raii::PipelineLayout pipelineLayout_;
  ::vk::raii::DescriptorPool pool_;
  ::vk::raii::DescriptorSets sets_;
  ::vk::raii::Pipeline emit_;
  ::vk::raii::Pipeline bounce_;
  TraceLayout traceLayout_;
  ::vk::raii::CommandPool commandPool_;
  ::vk::raii::CommandBuffers commands_;
  ::vk::raii::Fence fence_;
  std::optional<::vk::raii::QueryPool> queries_;
  // The queries' results, copied there by the queue (copyQueriesToHost: lavapipe's query read
  // waits for its whole queue).
  std::optional<DeviceBuffer> stamps_;
  double periodNs_ = 0.0;
  bool inFlight_ = false;
  std::uint32_t inFlightBounces_ = 0;
  std::uint64_t submitted_ = 0;  // the last submission's number; the one in flight if any
  std::deque<std::pair<std::uint64_t, LightPathTimings>> banked_;  // oldest first
  std::optional<LightPathSurfaces> surfaces_;
  std::optional<Working> working_;
  std::optional<Inputs> inputs_;
  std::optional<DeviceBuffer> vpls_;
  VplBuffers shared_;
  std::optional<ExportedSemaphores> semaphores_;
};

}  // namespace lgh::vk
