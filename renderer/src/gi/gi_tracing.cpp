#include "gi/gi_tracing.hpp"

#include "lgh/error.hpp"

namespace lgh {

GiTracing::GiTracing(ShadowDevice* device) : device_(device) {}
GiTracing::~GiTracing() = default;

GiTracing::Session GiTracing::begin(const CachedScene& scene, ShadowTracing requested,
                                    const std::string& field) {
  vk::ShadowTracer* tracer = device_ != nullptr ? device_->tracer() : nullptr;
  if (tracer == nullptr) {
    const std::string reason =
        device_ != nullptr ? device_->unavailableReason() : "this renderer traces no rays";
    throw Error(
        ErrorCode::Unavailable,
        "global illumination traces light paths, and this machine cannot trace rays: " + reason,
        field);
  }
  Session session;
  session.path = chooseTracePath(*tracer, requested);
  try {
    session.scene = &device_->traceScene(scene, &session.asBuildGpuMs);
    if (!transport_ || epoch_ != device_->epoch()) {
      transport_ = std::make_unique<HitBatchTransport>(*tracer);
      vplTransport_ = std::make_unique<VplTransport>(*tracer);
      epoch_ = device_->epoch();
    }
  } catch (const Error& error) {
    transport_.reset();
    vplTransport_.reset();
    device_->reset(error.message());
    throw;
  }
  session.transport = transport_.get();
  session.vpls = vplTransport_.get();
  return session;
}

double GiTracing::trace(const Session& session, const vk::HitBatchShape& shape) {
  try {
    return session.transport->trace(*session.scene, session.path, shape);
  } catch (const Error& error) {
    transport_.reset();
    vplTransport_.reset();
    if (device_ != nullptr) device_->reset(error.message());
    throw;
  }
}

double GiTracing::traceLightPaths(const Session& session, const vk::LightPathScene& surfaces,
                                  const vk::LightPathBatch& batch) {
  try {
    return session.vpls->trace(*session.scene, session.path, surfaces, batch);
  } catch (const Error& error) {
    transport_.reset();
    vplTransport_.reset();
    if (device_ != nullptr) device_->reset(error.message());
    throw;
  }
}

ShadowDevice::SubmissionMark GiTracing::lightPathMark() const {
  if (device_ == nullptr || !vplTransport_) return {};
  return device_->mark();
}

double GiTracing::collectGpuMs() {
  vk::ShadowTracer* tracer = device_ != nullptr ? device_->tracer() : nullptr;
  if (tracer == nullptr || !transport_) return 0.0;
  return tracer->collectHitTimings().traceGpuMs;
}

}  // namespace lgh
