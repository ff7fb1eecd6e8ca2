#include "server.hpp"

#include <sys/socket.h>

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "clock.hpp"
#include "http_conventions.hpp"
#include "http_util.hpp"
#include "logging.hpp"
#include "routes.hpp"

namespace lghd {
namespace {

// When the current request's headers were read. httplib serves a connection's requests one after
// another on one worker thread, from the pre-routing handler to the logger, so a thread-local
// clock is the request's clock.
thread_local std::optional<Clock::time_point> requestStart;

// A bounded label for metrics: the route's template (/v1/jobs/{id}), not the raw path.
std::string routeLabel(const std::string& path) {
  const RouteSpec* route = matchRoute(path);
  if (route == nullptr) return "other";
  if (route->path.ends_with("{schema}")) return "/proto";
  return std::string(route->path);
}

bool isProbe(const std::string& path) { return path == "/healthz" || path == "/readyz"; }

// Compares in time independent of where the strings differ.
bool sameToken(const std::string& given, const std::string& expected) {
  unsigned char difference = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < given.size(); ++i) {
    difference |= static_cast<unsigned char>(given[i] ^ expected[i % expected.size()]);
  }
  return difference == 0;
}

bool authorized(const httplib::Request& request, const std::string& token) {
  const std::string header = request.get_header_value("Authorization");
  const std::string prefix = "Bearer ";
  return header.starts_with(prefix) && sameToken(header.substr(prefix.size()), token);
}

// httplib 0.11 applies its body limit only to bodies with a Content-Length: a chunked body would
// be read whole, however large. Refuse it before the body is read, and close the connection
// rather than read the rest.
bool refusedChunkedBody(const httplib::Request& request, httplib::Response& response) {
  if (!request.has_header("Transfer-Encoding")) return false;
  response.set_header("Connection", "close");
  sendError(response, ApiError(411, "length_required",
                               "send the body with a Content-Length (chunked request bodies are "
                               "not accepted)",
                               "Transfer-Encoding"));
  return true;
}

bool refusedUnauthorized(const DaemonContext& context, const httplib::Request& request,
                         httplib::Response& response) {
  const std::string& token = context.config.authToken;
  if (token.empty() || isProbe(request.path) || authorized(request, token)) return false;
  sendError(response,
            ApiError(401, "unauthorized", "missing or wrong bearer token", "Authorization"));
  return true;
}

httplib::Server::HandlerResponse preRouting(const DaemonContext& context,
                                            const httplib::Request& request,
                                            httplib::Response& response) {
  requestStart = Clock::now();
  response.set_header(kRequestIdHeader,
                      logging::requestIdFrom(request.get_header_value(kRequestIdHeader)));
  // CORS preflights carry no credentials: they are answered before authentication.
  if (answeredCorsOrOptions(context.config.corsOrigins, request, response)) {
    return httplib::Server::HandlerResponse::Handled;
  }
  if (refusedChunkedBody(request, response) || refusedUnauthorized(context, request, response) ||
      refusedMethodOrMediaType(request, response)) {
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

// httplib's own error answers (no route, body over the limit, unparsable request) get the same
// JSON body as ours; answers that have a body already pass through.
httplib::Server::HandlerResponse errorAnswer(const DaemonContext& context,
                                             const httplib::Request& request,
                                             httplib::Response& response) {
  if (!response.body.empty() || response.content_provider_) {
    return httplib::Server::HandlerResponse::Unhandled;
  }
  if (!response.has_header(kRequestIdHeader)) {
    response.set_header(kRequestIdHeader, logging::newRequestId());
  }
  switch (response.status) {
    case 404:
      sendError(response, ApiError(404, "not_found",
                                   fmt::format("no route {} {}", request.method, request.path)));
      break;
    case 413:
      sendError(response,
                ApiError(413, "too_large",
                         fmt::format("the request body is over this server's limit of {} bytes",
                                     context.config.limits.maxBodyBytes)));
      break;
    default:
      sendError(response,
                ApiError(response.status, response.status < 500 ? "bad_request" : "internal",
                         fmt::format("HTTP {}", response.status)));
  }
  return httplib::Server::HandlerResponse::Handled;
}

void exceptionAnswer(const httplib::Request& request, httplib::Response& response,
                     std::exception_ptr exception) {
  std::string what = "unknown exception";
  try {
    std::rethrow_exception(std::move(exception));
  } catch (const std::exception& error) {
    what = error.what();
  } catch (...) {
  }
  logging::event(spdlog::level::err, "unhandled_exception",
                 {{"request_id", requestIdOf(response)}, {"path", request.path}, {"error", what}});
  sendError(response,
            internalError("internal error; the log has the details under this request id"));
}

// Probes and scrapes come every few seconds: debug, so that they do not drown the log. A 503 is
// expected while starting or draining; a 500 or 504 is worth a warning.
spdlog::level::level_enum accessLogLevel(const std::string& path, int status) {
  if (status == 500 || status == 504) return spdlog::level::warn;
  if (isProbe(path) || path == "/metrics") return spdlog::level::debug;
  return spdlog::level::info;
}

void accessLog(DaemonContext& context, const httplib::Request& request,
               const httplib::Response& response) {
  const double seconds = requestStart ? secondsSince(*requestStart) : 0.0;
  requestStart.reset();
  context.metrics.recordRequest(routeLabel(request.path), request.method, response.status, seconds);
  logging::event(accessLogLevel(request.path, response.status), "request",
                 {{"request_id", requestIdOf(response)},
                  {"method", request.method},
                  {"path", request.path},
                  {"status", response.status},
                  {"ms", std::round(seconds * 1e6) / 1000.0},
                  {"bytes_in", request.body.size()},
                  {"bytes_out", response.body.size()},
                  {"remote", request.remote_addr}});
}

}  // namespace

void configureServer(httplib::Server& server, DaemonContext& context) {
  const std::size_t threads = static_cast<std::size_t>(context.config.httpThreads);
  // httplib owns the task queue it gets from this factory (its API takes a raw pointer).
  server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server.set_payload_max_length(context.config.limits.maxBodyBytes);
  server.set_tcp_nodelay(true);
  // httplib closes a keep-alive connection after 5 requests by default; clients that keep one
  // open (load balancers, benchmarks) should not pay a reconnect that often.
  server.set_keep_alive_max_count(10000);
  server.set_pre_routing_handler(
      [&context](const httplib::Request& request, httplib::Response& response) {
        return preRouting(context, request, response);
      });
  server.set_error_handler(httplib::Server::HandlerWithResponse(
      [&context](const httplib::Request& request, httplib::Response& response) {
        return errorAnswer(context, request, response);
      }));
  server.set_exception_handler(exceptionAnswer);
  server.set_logger([&context](const httplib::Request& request, const httplib::Response& response) {
    accessLog(context, request, response);
  });
  addRenderRoutes(server, context);
  addThumbnailRoutes(server, context);
  addJobRoutes(server, context);
  addStatusRoutes(server, context);
  addDocumentRoutes(server);
  addBenchmarkRoutes(server, context);
}

bool HttpServer::raiseListenBacklog(int backlog) { return ::listen(svr_sock_, backlog) == 0; }

int bindServer(HttpServer& server, const std::string& host, int port) {
  constexpr int kListenBacklog = 1024;  // the kernel caps it at net.core.somaxconn
  const int bound =
      port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (bound >= 0 && !server.raiseListenBacklog(kListenBacklog)) {
    logging::event(spdlog::level::warn, "listen_backlog",
                   {{"note", "could not raise the listen backlog; bursts may see resets"}});
  }
  return bound;
}

}  // namespace lghd
