// POST /v1/render: a render request as JSON, or multipart/form-data with the request in a part
// named "request" and the scene uploaded in "file" parts. Answers the image, or JSON when the
// client accepts application/json.
#include "clock.hpp"
#include "http_conventions.hpp"
#include "http_util.hpp"
#include "render_response.hpp"
#include "routes.hpp"
#include "uploads.hpp"

namespace lghd {
namespace {

std::string_view imageMimeType(lgh::ImageFormat format) {
  return format == lgh::ImageFormat::Png ? "image/png" : "image/x-exr";
}

lgh::RenderRequest parseUpload(const httplib::Request& http, const lgh::RequestLimits& limits) {
  const nlohmann::json json = requestPartJson(http);
  const std::vector<UploadedFile> files = uploadedFiles(http);
  if (files.empty()) return lgh::parseRenderRequest(json, limits);
  if (json.contains("scene")) {
    throw badRequest("the scene comes from the uploaded files: leave scene out of the request",
                     "/scene");
  }
  lgh::RenderRequest request = lgh::parseRenderRequest(json, limits);
  request.scene = uploadedScene(files);
  return request;
}

lgh::RenderRequest parseRender(const httplib::Request& http, const lgh::RequestLimits& limits) {
  if (http.is_multipart_form_data()) return parseUpload(http, limits);
  return lgh::parseRenderRequest(http.body.empty() ? std::string("{}") : http.body, limits);
}

void render(DaemonContext& context, const httplib::Request& http, httplib::Response& response) {
  const std::string requestId = requestIdOf(response);
  const Clock::time_point deadline = deadlineFor(http, context.config);
  lgh::RenderRequest request = parseRender(http, context.requestLimits);
  // Negotiated before the render: a 406 costs no GPU time.
  const std::string mime =
      chooseMediaType(http, {imageMimeType(request.output.format), "application/json"});
  const int width = request.output.width;
  const int height = request.output.height;
  const auto job = context.queue.submit({std::move(request)}, requestId, deadline);
  RenderTicket& ticket = *job->tickets.front();
  const lgh::RenderResult result = ticket.wait(deadline);

  const double queueMs =
      millisecondsBetween(job->enqueued, ticket.started().value_or(job->enqueued));
  const RenderAnswer answer{result, width, height, queueMs, requestId, ticket.gpu()};
  setRenderHeaders(response, answer);
  if (mime == "application/json") {
    sendJson(response, 200, renderResponseJson(answer));
    return;
  }
  response.set_content(reinterpret_cast<const char*>(result.encoded.data()), result.encoded.size(),
                       result.mimeType);
}

}  // namespace

void addRenderRoutes(httplib::Server& server, DaemonContext& context) {
  server.Post("/v1/render",
              guarded([&context](const httplib::Request& http, httplib::Response& response) {
                render(context, http, response);
              }));
}

}  // namespace lghd
