// POST /v1/jobs (202 + Location), GET /v1/jobs/{id} (status, progress, ETA),
// GET /v1/jobs/{id}/result (the result once it succeeded) and DELETE /v1/jobs/{id} (cancel, or
// forget a finished job). The job store (jobs.hpp) does the work.
#include "http_conventions.hpp"
#include "http_util.hpp"
#include "job_work.hpp"
#include "jobs.hpp"
#include "render_response.hpp"
#include "routes.hpp"

namespace lghd {
namespace {

constexpr const char* kJobPath = R"(/v1/jobs/([^/]+))";

ApiError unknownJob(const std::string& id) {
  return ApiError(404, "not_found",
                  "no job " + id + " (unknown, deleted, or expired after its time to live)", "id");
}

void submitJob(DaemonContext& context, const httplib::Request& http, httplib::Response& response) {
  if (http.is_multipart_form_data()) {
    throw badRequest(
        "a job request is JSON (application/json); upload scenes inline as "
        "scene.glb_base64, or give asset paths",
        "Content-Type");
  }
  std::unique_ptr<JobWork> work = parseJobWork(parseJsonBody(http.body), context.config,
                                               context.requestLimits, context.metrics);
  const nlohmann::json status = context.jobs.submit(std::move(work), requestIdOf(response));
  response.set_header("Location", status.at("href").get<std::string>());
  sendJson(response, 202, status);
}

void answerRenderResult(const JobResult& result, const httplib::Request& http,
                        httplib::Response& response) {
  const std::string mime = chooseMediaType(http, {result.render->mimeType, "application/json"});
  const RenderAnswer answer{*result.render, result.width, result.height, result.queueMs,
                            requestIdOf(response), result.gpu};
  setRenderHeaders(response, answer);
  if (mime == "application/json") {
    sendJson(response, 200, renderResponseJson(answer));
    return;
  }
  const auto& bytes = result.render->encoded;
  response.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(),
                       result.render->mimeType);
}

void answerResult(DaemonContext& context, const httplib::Request& http,
                  httplib::Response& response) {
  const std::shared_ptr<const JobResult> result = context.jobs.result(http.matches[1].str());
  if (result->render) {
    answerRenderResult(*result, http, response);
    return;
  }
  chooseMediaType(http, {result->mime});
  for (const auto& [name, value] : result->headers) response.set_header(name, value);
  response.set_content(result->body, result->mime);
}

}  // namespace

void addJobRoutes(httplib::Server& server, DaemonContext& context) {
  server.Post("/v1/jobs",
              guarded([&context](const httplib::Request& http, httplib::Response& response) {
                submitJob(context, http, response);
              }));
  server.Get(kJobPath,
             guarded([&context](const httplib::Request& http, httplib::Response& response) {
               const std::string id = http.matches[1].str();
               const auto status = context.jobs.status(id);
               if (!status) throw unknownJob(id);
               sendJson(response, 200, *status);
             }));
  server.Delete(kJobPath,
                guarded([&context](const httplib::Request& http, httplib::Response& response) {
                  const std::string id = http.matches[1].str();
                  const auto status = context.jobs.remove(id);
                  if (!status) throw unknownJob(id);
                  sendJson(response, 200, *status);
                }));
  server.Get(std::string(kJobPath) + "/result",
             guarded([&context](const httplib::Request& http, httplib::Response& response) {
               answerResult(context, http, response);
             }));
}

}  // namespace lghd
