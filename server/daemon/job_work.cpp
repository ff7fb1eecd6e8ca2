#include "job_work.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "thumbnails.hpp"
#include "zip_writer.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;

constexpr std::size_t kMetadataBytes =
    std::size_t{16} * 1024;  // file headers and metadata text chunks

// The largest file the image encoders write for `output`: PNG rows stored unfiltered in the
// worst case (4 bytes per pixel plus a filter byte per row), EXR half or float RGBA with a tenth
// for compression that does not pay off.
std::size_t encodedBound(const lgh::OutputSettings& output) {
  const auto pixels =
      static_cast<std::size_t>(output.width) * static_cast<std::size_t>(output.height);
  switch (output.format) {
    case lgh::ImageFormat::Png:
      return pixels * 4 + static_cast<std::size_t>(output.height) + kMetadataBytes;
    case lgh::ImageFormat::ExrHalf:
      return pixels * 8 * 11 / 10 + kMetadataBytes;
    case lgh::ImageFormat::ExrFloat:
      return pixels * 16 * 11 / 10 + kMetadataBytes;
  }
  return pixels * 16 + kMetadataBytes;
}

// Errors about the job's "request" member name it: /request/...
ApiError underRequest(const ApiError& error) {
  const std::string& field = error.field();
  if (!field.starts_with('/')) return error;
  ApiError moved(error.status(), error.code(), error.message(),
                 field == "/" ? "/request" : "/request" + field);
  return moved.withRetryAfter(error.retryAfterSeconds());
}

template <class Parse>
auto parsedUnderRequest(Parse parse) {
  try {
    return parse();
  } catch (const lgh::Error& error) {
    throw underRequest(fromLghError(error));
  } catch (const ApiError& error) {
    throw underRequest(error);
  }
}

lgh::RenderResult withoutPixels(lgh::RenderResult result) {
  result.pixels.release();  // only the encoded image is answered
  return result;
}

ApiError tooLarge(std::string message, std::string field) {
  return fromLghError(lgh::Error(lgh::ErrorCode::TooLarge, std::move(message), std::move(field)));
}

// --- render
// ---------------------------------------------------------------------------------------

class RenderWork final : public JobWork {
 public:
  explicit RenderWork(lgh::RenderRequest request) : request_(std::move(request)) {}

  const char* kind() const override { return "render"; }
  std::size_t size() const override { return 1; }
  std::pair<std::optional<lgh::RenderRequest>, std::optional<ApiError>> item(
      std::size_t /*i*/) const override {
    return {request_, std::nullopt};
  }
  bool record(std::size_t /*i*/, RenderOutcome outcome) override {
    outcome_ = std::move(outcome);
    return !outcome_->error;
  }
  JobResult finish() override {
    if (!outcome_ || outcome_->error) {
      throw outcome_ ? *outcome_->error : internalError("the render job ended without a render");
    }
    JobResult result;
    result.width = request_.output.width;
    result.height = request_.output.height;
    result.queueMs = outcome_->queueMs;
    result.gpu = outcome_->gpu;
    result.render =
        std::make_shared<const lgh::RenderResult>(withoutPixels(std::move(*outcome_->result)));
    result.mime = result.render->mimeType;
    return result;
  }
  std::size_t resultBytesBound() const override { return encodedBound(request_.output); }

 private:
  lgh::RenderRequest request_;
  std::optional<RenderOutcome> outcome_;
};

// --- thumbnails
// -------------------------------------------------------------------------------------

class ThumbnailsWork final : public JobWork {
 public:
  ThumbnailsWork(ThumbnailBatch batch, Metrics& metrics)
      : batch_(std::move(batch)), metrics_(metrics) {}

  const char* kind() const override { return "thumbnails"; }
  std::size_t size() const override { return batch_.items.size(); }
  std::pair<std::optional<lgh::RenderRequest>, std::optional<ApiError>> item(
      std::size_t i) const override {
    const ThumbnailItem& thumbnail = batch_.items[i];
    return {thumbnail.request, thumbnail.error};
  }
  bool record(std::size_t i, RenderOutcome outcome) override {
    const ThumbnailItem& thumbnail = batch_.items[i];
    metrics_.recordThumbnail(outcome.result ? "ok" : "error");
    if (outcome.result) {
      zip_.addStored(thumbnail.fileName, std::move(outcome.result->encoded),
                     zipCommentNamingGpu(outcome.gpu));
      ++ok_;
      return true;
    }
    ApiError error = *outcome.error;
    // The renderer names the scene /scene/...; the client named it in the batch.
    if (error.field().starts_with("/scene")) {
      error = ApiError(error.status(), error.code(), error.message(), thumbnail.assetField);
    }
    errors_.push_back({{"index", i},
                       {"total", batch_.items.size()},
                       {"asset", thumbnail.asset},
                       {"view", thumbnail.view},
                       {"file", thumbnail.fileName},
                       {"error", error.body("")["error"]}});
    return true;
  }
  JobResult finish() override {
    if (!errors_.empty()) zip_.addDeflated("errors.json", errors_.dump(2) + "\n");
    JobResult result;
    result.body = zip_.finish();
    result.mime = "application/zip";
    result.headers = {{"X-Lgh-Thumbnails-Ok", std::to_string(ok_)},
                      {"X-Lgh-Thumbnails-Failed", std::to_string(errors_.size())},
                      {"Content-Disposition", "attachment; filename=\"thumbnails.zip\""}};
    return result;
  }
  std::size_t resultBytesBound() const override {
    std::size_t bytes = kMetadataBytes;
    for (const ThumbnailItem& item : batch_.items) {
      bytes += item.request ? encodedBound(item.request->output) : 0;
      bytes += 1024;  // its ZIP entry, or its line of errors.json
    }
    return bytes;
  }
  std::size_t failedItems() const override { return errors_.size(); }

 private:
  ThumbnailBatch batch_;
  Metrics& metrics_;
  ZipWriter zip_;
  json errors_ = json::array();
  std::size_t ok_ = 0;
};

// --- benchmark
// ------------------------------------------------------------------------------------

class BenchmarkWork final : public JobWork {
 public:
  BenchmarkWork(lgh::RenderRequest request, int warmup, int iterations)
      : request_(std::move(request)), warmup_(warmup), iterations_(iterations) {}

  const char* kind() const override { return "benchmark"; }
  std::size_t size() const override {
    return static_cast<std::size_t>(warmup_) + static_cast<std::size_t>(iterations_);
  }
  std::pair<std::optional<lgh::RenderRequest>, std::optional<ApiError>> item(
      std::size_t /*i*/) const override {
    return {request_, std::nullopt};
  }
  bool record(std::size_t i, RenderOutcome outcome) override {
    if (outcome.error) {
      error_ = std::move(outcome.error);
      return false;
    }
    lgh::RenderResult& result = *outcome.result;
    if (i >= static_cast<std::size_t>(warmup_)) {
      runs_.push_back(result.timings);
      gpus_.push_back(outcome.gpu);
      sceneCacheHits_ += result.sceneCacheHit ? 1 : 0;
    }
    device_ = result.device.toJson();
    paths_ = result.decisions;
    warnings_ = result.warnings;
    return true;
  }
  JobResult finish() override {
    if (error_) throw *error_;
    JobResult result;
    result.body = resultJson().dump(2) + "\n";
    result.mime = "application/json";
    return result;
  }
  std::size_t resultBytesBound() const override {
    return kMetadataBytes + static_cast<std::size_t>(iterations_) * 64;
  }

 private:
  // Each row's median over the timed renders, in the order of the first run.
  lgh::TimingTable medianTimings() const {
    lgh::TimingTable median;
    for (const lgh::TimingRow& row : runs_.front().rows) {
      std::vector<double> values;
      for (const lgh::TimingTable& run : runs_) values.push_back(run.get(row.name));
      std::sort(values.begin(), values.end());
      median.add(row.name, row.clock, values[values.size() / 2]);
    }
    return median;
  }

  json resultJson() const {
    json totals = json::array();
    for (const lgh::TimingTable& run : runs_) totals.push_back(run.get("total"));
    return {{"kind", "benchmark"},
            {"warmup", warmup_},
            {"iterations", iterations_},
            {"width", request_.output.width},
            {"height", request_.output.height},
            {"timings", medianTimings().toJson()},
            {"total_ms", std::move(totals)},
            {"gpus", gpus_},
            {"scene_cache_hits", sceneCacheHits_},
            {"device", device_},
            {"paths", paths_},
            {"warnings", warnings_}};
  }

  lgh::RenderRequest request_;
  int warmup_;
  int iterations_;
  std::vector<lgh::TimingTable> runs_;
  std::vector<int> gpus_;  // the render worker of each timed render
  std::optional<ApiError> error_;
  int sceneCacheHits_ = 0;
  json device_;
  std::map<std::string, std::string> paths_;
  std::vector<std::string> warnings_;
};

lgh::RenderRequest renderRequestOf(const json& body, const lgh::RequestLimits& limits) {
  const json request = body.value("request", json::object());
  return parsedUnderRequest([&] { return lgh::parseRenderRequest(request, limits); });
}

std::unique_ptr<JobWork> thumbnailsWork(const json& body, const DaemonConfig& config,
                                        const lgh::RequestLimits& limits, Metrics& metrics) {
  const json& request = body.at("request");
  if (request.value("format", "zip") != "zip") {
    throw badRequest("a thumbnails job's result is a ZIP: leave format out or make it \"zip\"",
                     "/request/format");
  }
  ThumbnailBatch batch = parsedUnderRequest(
      [&] { return parseThumbnailBatch(request, {}, limits, config.jobs.maxBatch); });
  return std::make_unique<ThumbnailsWork>(std::move(batch), metrics);
}

std::unique_ptr<JobWork> benchmarkWork(const json& body, const DaemonConfig& config,
                                       const lgh::RequestLimits& limits) {
  const int warmup = body.value("warmup", 1);
  const int iterations = body.value("iterations", 10);
  if (warmup + iterations > config.jobs.maxBatch) {
    throw tooLarge(fmt::format("warmup + iterations is {}, over this server's limit of {} renders "
                               "in one job",
                               warmup + iterations, config.jobs.maxBatch),
                   "/iterations");
  }
  return std::make_unique<BenchmarkWork>(renderRequestOf(body, limits), warmup, iterations);
}

}  // namespace

std::size_t JobResult::bytes() const { return body.size() + (render ? render->encoded.size() : 0); }

std::unique_ptr<JobWork> parseJobWork(const json& body, const DaemonConfig& config,
                                      const lgh::RequestLimits& limits, Metrics& metrics) {
  if (!body.is_object()) throw badRequest("a job request must be a JSON object", "/");
  try {
    lgh::validateAgainstProtoSchema(body, "job-request.schema.json");
  } catch (const lgh::Error& error) {
    throw fromLghError(error);
  }
  const std::string kind = body.at("kind").get<std::string>();
  if (kind == "render") return std::make_unique<RenderWork>(renderRequestOf(body, limits));
  if (kind == "thumbnails") return thumbnailsWork(body, config, limits, metrics);
  if (kind == "benchmark") return benchmarkWork(body, config, limits);
  // The schema's enum lists the kinds above; a kind added there but not here is a bug.
  throw internalError(fmt::format("job kind \"{}\" is in the schema but not implemented", kind));
}

}  // namespace lghd
