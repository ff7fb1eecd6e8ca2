// What one job (POST /v1/jobs) renders and how its renders become the result, by kind:
//   render      one render request; the result is answered like POST /v1/render
//   thumbnails  a thumbnails request (assets x views); the result is the ZIP of POST /v1/thumbnails
//   benchmark   one render request rendered warmup + iterations times; the result is JSON with
//               each pass's median time (proto/benchmark-result.schema.json)
// The job store (jobs.hpp) runs the renders one by one through the render queue, so that they take
// their turns with synchronous requests, and hands each outcome to record().
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "api_error.hpp"
#include "config.hpp"
#include "lgh/renderer.hpp"
#include "metrics.hpp"

namespace lghd {

// A finished job's answer on GET /v1/jobs/{id}/result.
struct JobResult {
  // A render job: the render (its pixels dropped; the encoded image kept), answered as
  // POST /v1/render answers (image or render-response JSON, with the X-Lgh-* headers).
  std::shared_ptr<const lgh::RenderResult> render;
  int width = 0;
  int height = 0;
  double queueMs = 0.0;
  int gpu = -1;  // the render worker it ran on (its place in --gpus)
  // Other kinds: the body, its media type and extra headers.
  std::string body;
  std::string mime;
  std::vector<std::pair<std::string, std::string>> headers;

  std::size_t bytes() const;
};

// One render's outcome: the result, or the error it was answered with.
struct RenderOutcome {
  std::optional<lgh::RenderResult> result;
  std::optional<ApiError> error;
  double queueMs = 0.0;
  int gpu = -1;  // the render worker that rendered it (-1: none)
};

class JobWork {
 public:
  virtual ~JobWork() = default;
  virtual const char* kind() const = 0;
  // Renders the job takes (items that fail before rendering included).
  virtual std::size_t size() const = 0;
  // Item i's render request, or the error that stops it before rendering (a thumbnail's bad
  // asset path).
  virtual std::pair<std::optional<lgh::RenderRequest>, std::optional<ApiError>> item(
      std::size_t i) const = 0;
  // Item i's outcome, in order. Returns false when the job cannot succeed any more (a render
  // job's render failed): the store stops rendering and finish() reports the error.
  virtual bool record(std::size_t i, RenderOutcome outcome) = 0;
  // The result once every item is recorded; throws the ApiError that failed the job.
  virtual JobResult finish() = 0;
  // An upper bound of the result's size, reserved against the job memory budget at submission.
  virtual std::size_t resultBytesBound() const = 0;
  // Items that failed (thumbnails whose entry carries an error).
  virtual std::size_t failedItems() const { return 0; }
};

// Parses a job request (proto/job-request.schema.json) into its work. Throws ApiError naming the
// field (400/413/422) as the synchronous routes do; the limits are theirs, except that a thumbnails
// job may hold up to `jobLimits.maxBatch` thumbnails and a benchmark up to as many renders.
std::unique_ptr<JobWork> parseJobWork(const nlohmann::json& body, const DaemonConfig& config,
                                      const lgh::RequestLimits& limits, Metrics& metrics);

}  // namespace lghd
