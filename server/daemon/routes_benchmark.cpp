// POST /v1/benchmark (start `lgh-bench gi` with the body's options, 202), GET /v1/benchmark (its
// status and progress), GET /v1/benchmark/result (the JSON document of the last one that finished,
// as `lgh-bench gi --json` prints it). One at a time: 429 while one runs. docs/DAEMON.md.
#include "benchmark_request.hpp"
#include "benchmark_runner.hpp"
#include "http_util.hpp"
#include "routes.hpp"

namespace lghd {
namespace {

BenchmarkRunner& runnerOf(const DaemonContext& context) {
  if (context.benchmarks == nullptr) throw unavailable("this daemon runs no benchmarks");
  return *context.benchmarks;
}

void start(DaemonContext& context, const httplib::Request& http, httplib::Response& response) {
  BenchmarkRunner& runner = runnerOf(context);
  const nlohmann::json body = parseJsonBody(http.body);
  parseBenchmarkRequest(body, context.requestLimits);  // answers mistakes now, not in the child
  runner.start(body);
  response.set_header("Location", "/v1/benchmark");
  sendJson(response, 202, runner.status());
}

void status(DaemonContext& context, httplib::Response& response) {
  sendJson(response, 200, runnerOf(context).status());
}

void result(DaemonContext& context, httplib::Response& response) {
  const std::optional<std::string> document = runnerOf(context).result();
  if (!document) {
    sendError(response, ApiError(404, "not_found", "no benchmark has finished yet"));
    return;
  }
  response.status = 200;
  response.set_content(*document, "application/json");
}

}  // namespace

void addBenchmarkRoutes(httplib::Server& server, DaemonContext& context) {
  server.Post("/v1/benchmark",
              guarded([&context](const httplib::Request& http, httplib::Response& response) {
                start(context, http, response);
              }));
  server.Get("/v1/benchmark",
             guarded([&context](const httplib::Request&, httplib::Response& response) {
               status(context, response);
             }));
  server.Get("/v1/benchmark/result",
             guarded([&context](const httplib::Request&, httplib::Response& response) {
               result(context, response);
             }));
}

}  // namespace lghd
