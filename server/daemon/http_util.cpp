#include "http_util.hpp"

#include <charconv>

#include <fmt/format.h>

#include "lgh/request.hpp"
#include "logging.hpp"

namespace lghd {

std::string requestIdOf(const httplib::Response& response) {
  return response.get_header_value(kRequestIdHeader);
}

void sendJson(httplib::Response& response, int status, const nlohmann::json& body) {
  response.status = status;
  response.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                       "application/json");
}

void sendError(httplib::Response& response, const ApiError& error) {
  if (error.retryAfterSeconds() > 0) {
    response.set_header("Retry-After", std::to_string(error.retryAfterSeconds()));
  }
  if (error.status() == 401) response.set_header("WWW-Authenticate", "Bearer realm=\"lghd\"");
  sendJson(response, error.status(), error.body(requestIdOf(response)));
}

nlohmann::json parseJsonBody(const std::string& body) {
  if (body.empty()) return nlohmann::json::object();
  return lgh::parseRequestJson(body);
}

Clock::time_point deadlineFor(const httplib::Request& request, const DaemonConfig& config) {
  const auto now = Clock::now();
  const std::string header = request.get_header_value("X-Lgh-Deadline-Ms");
  if (header.empty()) return now + config.deadline;
  long long milliseconds = 0;
  const auto [end, error] =
      std::from_chars(header.data(), header.data() + header.size(), milliseconds);
  if (error != std::errc() || end != header.data() + header.size() || milliseconds <= 0) {
    throw badRequest("must be a positive whole number of milliseconds", "X-Lgh-Deadline-Ms");
  }
  return now + std::min<std::chrono::milliseconds>(std::chrono::milliseconds(milliseconds),
                                                   config.deadline);
}

std::string headerSafe(const std::string& value) {
  std::string safe = value.substr(0, 4096);
  for (char& c : safe) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = ' ';
  }
  return safe;
}

Handler guarded(Handler handler) {
  return
      [handler = std::move(handler)](const httplib::Request& request, httplib::Response& response) {
        try {
          handler(request, response);
        } catch (const ApiError& error) {
          sendError(response, error);
        } catch (const lgh::Error& error) {
          sendError(response, fromLghError(error));
        } catch (const std::exception& error) {
          logging::event(spdlog::level::err, "unhandled_exception",
                         {{"request_id", requestIdOf(response)}, {"error", error.what()}});
          sendError(response, internalError("internal error; the log has the details under this "
                                            "request id"));
        }
      };
}

}  // namespace lghd
