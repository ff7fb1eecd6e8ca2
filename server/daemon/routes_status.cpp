// GET /healthz (liveness: the process serves HTTP), /readyz (at least one render worker's context
// is up and its self-test render passed; 503 while starting or shutting down; the body lists each
// worker), /v1/info (with a gpus array: each worker) and /metrics.
#include <httplib.h>

#include "http_util.hpp"
#include "process_metrics.hpp"
#include "routes.hpp"
#include "version.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;

json limitsJson(const DaemonConfig& config) {
  const Limits& limits = config.limits;
  return {{"max_body_bytes", limits.maxBodyBytes}, {"max_width", limits.maxWidth},
          {"max_height", limits.maxHeight},        {"max_pixels", limits.maxPixels},
          {"max_lights", limits.maxLights},        {"max_vpls", limits.maxVpls},
          {"max_triangles", limits.maxTriangles},  {"max_texture_size", limits.maxTextureSize},
          {"max_batch", limits.maxBatch},          {"queue_depth", config.queueDepth},
          {"deadline_ms", config.deadline.count()}};
}

json jobLimitsJson(const JobLimits& jobs) {
  return {{"max_jobs", jobs.maxJobs},
          {"memory_budget_bytes", jobs.memoryBytes},
          {"ttl_seconds", jobs.ttl.count()},
          {"max_batch", jobs.maxBatch},
          {"deadline_ms", jobs.renderDeadline.count()}};
}

json buildJson() {
  return {{"version", kVersion},
          {"build_type", kBuildType},
          {"compiler", kCompiler},
          {"image_io", kImageIo},
          {"httplib", CPPHTTPLIB_VERSION}};
}

json cacheJson(const RuntimeGauges& gauges) {
  return {{"hits", gauges.sceneCacheHits},
          {"misses", gauges.sceneCacheMisses},
          {"entries", gauges.sceneCacheEntries},
          {"bytes", gauges.sceneCacheBytes},
          {"budget_bytes", gauges.sceneCacheBudgetBytes}};
}

// Each render worker: its place in --gpus, its EGL device, its state and load, its scene cache.
json gpusJson(const DaemonContext& context) {
  json gpus = json::array();
  for (const RenderWorker::Status& worker : context.queue.workers()) {
    json entry = {{"gpu", worker.index},
                  {"device_index", worker.deviceIndex},
                  {"state", workerStateName(worker.state)},
                  {"queue_depth", worker.queuedRenders},
                  {"rendering", worker.rendering},
                  {"frames_in_flight", worker.framesInFlight},
                  {"scene_cache",
                   {{"hits", worker.cache.hits},
                    {"misses", worker.cache.misses},
                    {"entries", worker.cache.entries},
                    {"bytes", worker.cache.bytes},
                    {"budget_bytes", context.config.sceneCacheBytes}}}};
    entry["device_name"] = worker.device ? worker.device->glRenderer : "";
    entry["device"] = worker.device ? worker.device->toJson() : json();
    if (!worker.failure.empty()) entry["reason"] = worker.failure;
    gpus.push_back(std::move(entry));
  }
  return gpus;
}

// /readyz: each worker's state, so that a probe's log shows which GPU is out.
json gpuStatesJson(const DaemonContext& context) {
  json gpus = json::array();
  for (const RenderWorker::Status& worker : context.queue.workers()) {
    json entry = {{"gpu", worker.index}, {"state", workerStateName(worker.state)}};
    if (!worker.failure.empty()) entry["reason"] = worker.failure;
    gpus.push_back(std::move(entry));
  }
  return gpus;
}

// What the Vulkan loader and drivers offer (null until the probe has answered).
json vulkanJson(const std::optional<lgh::VulkanInfo>& vulkan) {
  return vulkan ? vulkan->toJson() : json{{"available", nullptr}};
}

json infoJson(const DaemonContext& context) {
  const RuntimeGauges gauges = context.queue.gauges();
  const std::optional<lgh::DeviceInfo> device = context.queue.device();
  const std::string reason = context.queue.notReadyReason();
  return {{"service", "lghd"},
          {"build", buildJson()},
          {"ready", reason.empty()},
          {"status", reason.empty() ? "ready" : reason},
          {"device", device ? device->toJson() : json()},
          {"vulkan", vulkanJson(context.queue.vulkan())},
          {"shadows", context.queue.shadows().toJson()},
          {"resources", context.queue.resources().toJson()},
          {"limits", limitsJson(context.config)},
          {"queue",
           {{"depth", gauges.queueDepth},
            {"capacity", gauges.queueCapacity},
            {"rendering", gauges.rendering}}},
          {"scene_cache", cacheJson(gauges)},
          {"gpus", gpusJson(context)},
          {"jobs", jobLimitsJson(context.config.jobs)},
          {"auth", !context.config.authToken.empty()},
          {"cors_origins", context.config.corsOrigins}};
}

}  // namespace

void addScrapeRoutes(httplib::Server& server, DaemonContext& context) {
  server.Get("/healthz", [](const httplib::Request&, httplib::Response& response) {
    sendJson(response, 200, {{"status", "ok"}});
  });
  server.Get("/readyz", [&context](const httplib::Request&, httplib::Response& response) {
    const std::string reason = context.queue.notReadyReason();
    if (reason.empty()) {
      sendJson(response, 200, {{"status", "ready"}, {"gpus", gpuStatesJson(context)}});
    } else {
      sendError(response, unavailable(reason));
    }
  });
  server.Get("/metrics", [&context](const httplib::Request&, httplib::Response& response) {
    response.set_content(context.metrics.exposition(context.queue.gauges()) +
                             context.jobs.exposition() + processMetricsExposition(),
                         "text/plain; version=0.0.4; charset=utf-8");
  });
}

void addStatusRoutes(httplib::Server& server, DaemonContext& context) {
  addScrapeRoutes(server, context);
  server.Get("/v1/info", guarded([&context](const httplib::Request&, httplib::Response& response) {
               sendJson(response, 200, infoJson(context));
             }));
}

void addDocumentRoutes(httplib::Server& server) {
  auto document = [](const std::string& name, httplib::Response& response) {
    response.set_content(lgh::protoDocument(name), "application/json");
  };
  // /openapi.json, and the JSON Schemas its relative $refs name, beside it and under /proto/.
  server.Get(R"(/(?:proto/)?([a-z0-9-]+\.schema\.json|openapi\.json))",
             guarded([document](const httplib::Request& request, httplib::Response& response) {
               document(request.matches[1].str(), response);
             }));
}

}  // namespace lghd
