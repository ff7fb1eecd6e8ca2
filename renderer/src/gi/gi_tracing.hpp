// The closest-hit side of a renderer, shared by the light paths (vpl_tracer.hpp) and the
// path-traced reference (path_traced_reference.hpp): the ShadowDevice's Vulkan tracer, the scene's
// acceleration structures on it, the tracing path, and the GL side of the tracer's hit buffers
// (one per tracer: its semaphore pair is the tracer's). One per FramePipeline.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gi/hit_batch_transport.hpp"
#include "lgh/request.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/shadow_device.hpp"

namespace lgh {

class GiTracing {
 public:
  explicit GiTracing(ShadowDevice* device);
  ~GiTracing();
  GiTracing(const GiTracing&) = delete;
  GiTracing& operator=(const GiTracing&) = delete;

  struct Session {
    const vk::TraceScene* scene = nullptr;
    vk::TracePath path = vk::TracePath::RayQuery;
    HitBatchTransport* transport = nullptr;
    double asBuildMs = -1.0;  // >= 0: this session built the acceleration structures
  };
  // Everything a batch needs for `scene`. Throws lgh::Error(Unavailable) naming `field` when this
  // machine cannot trace (the tracer's reason in the message), Invalid for a tracing path the
  // device lacks (/settings/shadow_path).
  Session begin(const CachedScene& scene, ShadowTracing requested, const std::string& field);

  // Traces one batch of the session: a Vulkan failure drops the tracer (the next frame makes a
  // new one) and is rethrown.
  double trace(const Session& session, const vk::HitBatchShape& shape);

  // The Vulkan GPU time of the batches since the last call.
  double collectGpuMs();

 private:
  ShadowDevice* device_;
  std::unique_ptr<HitBatchTransport> transport_;
  std::uint64_t epoch_ = 0;  // the ShadowDevice epoch transport_ belongs to
};

}  // namespace lgh
