// The ray-tracing side of GI, shared by the light paths (vpl_tracer.hpp) and the path-traced
// reference (path_traced_reference.hpp): the ShadowDevice's Vulkan tracer, the scene's
// acceleration structures on it, the tracing path, the GL side of the tracer's hit buffers (the
// reference's closest-hit batches) and of its VPL buffer (the light paths, traced in one Vulkan
// submission), one of each per tracer (their semaphore pairs are the tracer's). One per
// FramePipeline.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gi/hit_batch_transport.hpp"
#include "gi/vpl_transport.hpp"
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
    VplTransport* vpls = nullptr;
    // Set when this session built the acceleration structures: their GPU time, read later.
    std::function<double()> asBuildGpuMs;
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

  // Generates the light paths' VPLs in the session's VPL buffer (one Vulkan submission), with the
  // error handling of trace(). Returns the CPU milliseconds of the hand-over (VplTransport).
  double traceLightPaths(const Session& session, const vk::LightPathScene& surfaces,
                         const vk::LightPathBatch& batch);
  // Where the light paths' submissions stood after this frame's (ShadowDevice::mark); the
  // epoch is 0 when the frame traced none.
  ShadowDevice::SubmissionMark lightPathMark() const;
  ShadowDevice* device() const { return device_; }

 private:
  ShadowDevice* device_;
  std::unique_ptr<HitBatchTransport> transport_;
  std::unique_ptr<VplTransport> vplTransport_;
  std::uint64_t epoch_ = 0;  // the ShadowDevice epoch transport_ belongs to
};

}  // namespace lgh
