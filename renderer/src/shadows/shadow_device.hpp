// The Vulkan shadow tracer of the GL context's own GPU, created when a frame first needs it (the
// Vulkan instance and device cost 0.1-0.6 s), or the reason this machine has none. One per
// Renderer; the scene cache's acceleration structures belong to it (TraceSceneSlot::epoch), so
// the Renderer destroys the cache before it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "lgh/request.hpp"
#include "lgh/shadow_info.hpp"
#include "scene/scene_cache.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

class ShadowDevice {
 public:
  ShadowDevice();
  ~ShadowDevice();
  ShadowDevice(const ShadowDevice&) = delete;
  ShadowDevice& operator=(const ShadowDevice&) = delete;

  // The tracer, created on the first call; nullptr when there is none (unavailableReason()).
  // Needs the GL context current on the calling thread (it reads the GL device UUID).
  vk::ShadowTracer* tracer();
  const std::string& unavailableReason() const { return reason_; }
  // The tracer's state for reports; `transport`: how the frames hand rays over ("" before any).
  ShadowInfo info(const std::string& transport) const;
  // Changes whenever a new tracer is created: acceleration structures of an older epoch belong
  // to a device that is gone and must be built again.
  std::uint64_t epoch() const { return epoch_; }
  // A builder of acceleration structures for a prefetch thread, tagged with this epoch (a scene
  // built by an older tracer is built again when drawn); empty while there is no tracer yet:
  // the first shadowed frame makes it, on the render thread.
  SceneCache::TraceBuilder prefetchBuilder() const;
  // Drops the tracer after a failure (a lost device, say); the next tracer() makes a new one.
  void reset(const std::string& why);
  // The acceleration structures of `scene` on the tracer (which must exist): built on first use
  // and after a new tracer, cached with the scene. When this call built them, `*buildGpuMs` gets
  // the reader of their GPU build time (TraceScene::buildGpuMsReader: the build is not waited
  // for here) and `*buildWallMs` the call's wall time.
  const vk::TraceScene& traceScene(const CachedScene& scene,
                                   std::function<double()>* buildGpuMs = nullptr,
                                   double* buildWallMs = nullptr);

  // Where the tracer's submissions stood when a frame was drawn: the frame reads the GPU times
  // of its own submissions when it is taken (its GL fence has passed, so they are done), and
  // drawing the next frame waits for none of them.
  struct SubmissionMark {
    std::uint64_t epoch = 0;       // 0: no tracer
    std::uint64_t trace = 0;       // the last shadow-ray trace
    std::uint64_t lightPaths = 0;  // the last light-path submission
  };
  SubmissionMark mark() const;
  // The GPU time of the shadow-ray traces up to the mark that nobody read yet; nullopt when the
  // tracer has been replaced since the mark, or fails (logged: a frame's rows are not worth
  // failing a frame for).
  std::optional<double> traceGpuMs(const SubmissionMark& mark);
  std::optional<vk::LightPathTimings> lightPathTimings(const SubmissionMark& mark);

 private:
  std::unique_ptr<vk::ShadowTracer> tracer_;
  std::string reason_;
  bool tried_ = false;
  std::uint64_t epoch_ = 0;
};

// The GPU time of an acceleration-structure build from ShadowDevice::traceScene's reader, when a
// frame is taken: nullopt without a build, or when reading fails (logged, the row left out).
std::optional<double> readBuildGpuMs(const std::function<double()>& reader);

// The GL context's device UUID (GL_EXT_memory_object or GL_EXT_semaphore), or why there is none.
bool glDeviceUuid(vk::DeviceUuid& uuid, std::string& whyNot);

// The tracing path for a request's settings.shadow_path: auto is ray query where the device has
// it, else the pipeline. Throws lgh::Error(Invalid) naming /settings/shadow_path for a path the
// device lacks.
vk::TracePath chooseTracePath(const vk::ShadowTracer& tracer, ShadowTracing requested);

}  // namespace lgh
