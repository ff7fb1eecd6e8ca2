// POST /v1/thumbnails: a batch of assets rendered with auto-framed cameras. The whole batch is
// one job in the render queue (one slot); its renders are spread over the render workers (GPUs)
// and answered in the batch's order, each naming the GPU it ran on. Answers a ZIP (PNGs
// stored, failures in errors.json) or streams NDJSON, one line per thumbnail as it finishes and a
// summary line at the end.
#include <map>
#include <optional>

#include <fmt/format.h>

#include "clock.hpp"
#include "http_conventions.hpp"
#include "http_util.hpp"
#include "lgh/base64.hpp"
#include "logging.hpp"
#include "routes.hpp"
#include "thumbnails.hpp"
#include "zip_writer.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;

// One batch between the handler and the answer (the NDJSON stream outlives the handler).
class BatchRun {
 public:
  BatchRun(DaemonContext& context, ThumbnailBatch batch, std::string requestId)
      : context_(context), batch_(std::move(batch)), requestId_(std::move(requestId)) {}

  // Queues every item that passed validation. Throws ApiError 429/503 for the whole batch.
  void submit(Clock::time_point deadline) {
    perRender_ = deadline - Clock::now();
    std::vector<lgh::RenderRequest> requests;
    for (std::size_t i = 0; i < batch_.items.size(); ++i) {
      if (!batch_.items[i].request) continue;
      ticketOf_.emplace(i, requests.size());
      requests.push_back(*batch_.items[i].request);
    }
    if (!requests.empty()) job_ = context_.queue.submit(std::move(requests), requestId_, deadline);
  }

  std::size_t size() const { return batch_.items.size(); }
  const ThumbnailItem& item(std::size_t i) const { return batch_.items[i]; }

  // Waits for item i (in order). Each render gets the full deadline from when the previous one
  // was answered; the first counts from submission, queue wait included.
  struct Outcome {
    std::optional<lgh::RenderResult> result;
    std::optional<ApiError> error;
    int gpu = -1;  // the render worker that rendered it
  };
  Outcome wait(std::size_t i) {
    const ThumbnailItem& thumbnail = batch_.items[i];
    if (thumbnail.error) return record({std::nullopt, thumbnail.error});
    RenderTicket& ticket = *job_->tickets[ticketOf_.at(i)];
    const Clock::time_point deadline = std::max(job_->startDeadline, Clock::now() + perRender_);
    try {
      lgh::RenderResult result = ticket.wait(deadline);
      return record({std::move(result), std::nullopt, ticket.gpu()});
    } catch (const ApiError& error) {
      return record({std::nullopt, inBatchTerms(error, thumbnail), ticket.gpu()});
    }
  }

  // The renderer names the scene as /scene/...; the client named it in the batch.
  static ApiError inBatchTerms(const ApiError& error, const ThumbnailItem& item) {
    if (!error.field().starts_with("/scene")) return error;
    return ApiError(error.status(), error.code(), error.message(), item.assetField);
  }

  // The client went away: renders that have not started are skipped.
  void cancel() {
    if (job_) job_->cancelled = true;
  }

  json summary() const {
    return {
        {"status", "done"},  {"total", size()},          {"ok", ok_},
        {"failed", failed_}, {"request_id", requestId_}, {"elapsed_ms", millisecondsSince(start_)}};
  }
  std::size_t failed() const { return failed_; }
  std::size_t ok() const { return ok_; }

 private:
  Outcome record(Outcome outcome) {
    (outcome.result ? ok_ : failed_) += 1;
    context_.metrics.recordThumbnail(outcome.result ? "ok" : "error");
    return outcome;
  }

  DaemonContext& context_;
  ThumbnailBatch batch_;
  std::string requestId_;
  std::map<std::size_t, std::size_t> ticketOf_;  // item index -> ticket index
  std::shared_ptr<RenderJob> job_;
  Clock::time_point start_ = Clock::now();
  Clock::duration perRender_{};
  std::size_t ok_ = 0;
  std::size_t failed_ = 0;
};

json itemJson(const BatchRun& run, std::size_t i) {
  const ThumbnailItem& item = run.item(i);
  return {{"index", i},          {"total", run.size()}, {"completed", i + 1},
          {"asset", item.asset}, {"view", item.view},   {"file", item.fileName}};
}

json errorJson(const ApiError& error) { return error.body("")["error"]; }

json outcomeLine(const BatchRun& run, std::size_t i, const BatchRun::Outcome& outcome) {
  json line = itemJson(run, i);
  if (outcome.error) {
    line["status"] = "error";
    line["error"] = errorJson(*outcome.error);
    return line;
  }
  const lgh::RenderResult& result = *outcome.result;
  line["status"] = "ok";
  line["gpu"] = outcome.gpu;
  line["mime"] = result.mimeType;
  line["width"] = result.output.width;
  line["height"] = result.output.height;
  line["scene_cache"] = result.sceneCacheHit ? "hit" : "miss";
  line["timings"] = result.timings.toJson();
  line["warnings"] = result.warnings;
  line["image_base64"] = lgh::base64::encode(result.encoded);
  return line;
}

std::string ndjson(const json& line) {
  return line.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
}

void answerZip(BatchRun& run, httplib::Response& response) {
  ZipWriter zip;
  json errors = json::array();
  for (std::size_t i = 0; i < run.size(); ++i) {
    BatchRun::Outcome outcome = run.wait(i);
    if (outcome.result) {
      zip.addStored(run.item(i).fileName, std::move(outcome.result->encoded),
                    zipCommentNamingGpu(outcome.gpu));
    } else {
      json entry = itemJson(run, i);
      entry.erase("completed");
      entry["error"] = errorJson(*outcome.error);
      errors.push_back(std::move(entry));
    }
  }
  if (!errors.empty()) zip.addDeflated("errors.json", errors.dump(2) + "\n");
  response.set_header("X-Lgh-Thumbnails-Ok", std::to_string(run.ok()));
  response.set_header("X-Lgh-Thumbnails-Failed", std::to_string(run.failed()));
  response.set_header("Content-Disposition", "attachment; filename=\"thumbnails.zip\"");
  response.set_content(zip.finish(), "application/zip");
}

void answerNdjson(const std::shared_ptr<BatchRun>& run, httplib::Response& response) {
  response.set_chunked_content_provider(
      "application/x-ndjson", [run](std::size_t /*offset*/, httplib::DataSink& sink) {
        for (std::size_t i = 0; i < run->size(); ++i) {
          const std::string line = ndjson(outcomeLine(*run, i, run->wait(i)));
          if (!sink.write(line.data(), line.size())) {
            run->cancel();
            return false;
          }
        }
        const std::string summary = ndjson(run->summary());
        sink.write(summary.data(), summary.size());
        sink.done();
        return true;
      });
}

ThumbnailBatch parseBatch(DaemonContext& context, const httplib::Request& http) {
  const int maxBatch = context.config.limits.maxBatch;
  if (http.is_multipart_form_data()) {
    return parseThumbnailBatch(requestPartJson(http), uploadedFiles(http), context.requestLimits,
                               maxBatch);
  }
  return parseThumbnailBatch(parseJsonBody(http.body), {}, context.requestLimits, maxBatch);
}

void thumbnails(DaemonContext& context, const httplib::Request& http, httplib::Response& response) {
  const Clock::time_point deadline = deadlineFor(http, context.config);
  ThumbnailBatch batch = parseBatch(context, http);
  const ThumbnailBatch::Format format = batch.format;
  chooseMediaType(
      http, {format == ThumbnailBatch::Format::Zip ? "application/zip" : "application/x-ndjson"});
  auto run = std::make_shared<BatchRun>(context, std::move(batch), requestIdOf(response));
  run->submit(deadline);
  logging::event(spdlog::level::debug, "thumbnails_queued",
                 {{"request_id", requestIdOf(response)}, {"count", run->size()}});
  if (format == ThumbnailBatch::Format::Zip) {
    answerZip(*run, response);
  } else {
    answerNdjson(run, response);
  }
}

}  // namespace

void addThumbnailRoutes(httplib::Server& server, DaemonContext& context) {
  server.Post("/v1/thumbnails",
              guarded([&context](const httplib::Request& http, httplib::Response& response) {
                thumbnails(context, http, response);
              }));
}

}  // namespace lghd
