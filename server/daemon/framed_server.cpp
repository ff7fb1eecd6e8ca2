#include "framed_server.hpp"

#include <chrono>

#include <fmt/format.h>

#include "api_error.hpp"
#include "http_util.hpp"
#include "logging.hpp"

namespace lghd {
namespace {

const char* reasonPhrase(int status) {
  switch (status) {
    case 414:
      return "URI Too Long";
    case 431:
      return "Request Header Fields Too Large";
    case 505:
      return "HTTP Version Not Supported";
    default:
      return "Bad Request";
  }
}

const char* errorCode(int status) {
  switch (status) {
    case 414:
    case 431:
      return "too_large";
    case 505:
      return "http_version_not_supported";
    default:
      return "bad_request";
  }
}

std::chrono::microseconds duration(time_t seconds, time_t microseconds) {
  return std::chrono::seconds(seconds) + std::chrono::microseconds(microseconds);
}

// Methods httplib 0.11 reads no body for, whatever Content-Length says.
bool bodyIgnored(std::string_view head) {
  return !(head.starts_with("POST ") || head.starts_with("PUT ") || head.starts_with("PATCH ") ||
           head.starts_with("DELETE ") || head.starts_with("PRI "));
}

}  // namespace

bool FramedServer::process_and_close_socket(socket_t sock) {
  ConnectionStream stream(sock, duration(read_timeout_sec_, read_timeout_usec_),
                          duration(write_timeout_sec_, write_timeout_usec_));
  const auto stopping = [this] { return svr_sock_ == INVALID_SOCKET; };
  Next next = Next::KeepOpen;
  for (std::size_t served = 0; next == Next::KeepOpen && served < keep_alive_max_count_; ++served) {
    if (!stream.waitForRequest(std::chrono::seconds(keep_alive_timeout_sec_), stopping)) {
      next = Next::Close;
      break;
    }
    next = serveRequest(stream, served + 1 == keep_alive_max_count_);
  }
  if (next == Next::CloseLingering) {
    stream.lingeringClose();
  } else {
    stream.close();
  }
  return true;
}

FramedServer::Next FramedServer::serveRequest(ConnectionStream& stream, bool last) {
  const ConnectionStream::Head head = stream.readHead(limits_.maxHeadBytes);
  if (head.status == ConnectionStream::HeadStatus::TooLarge) {
    reject(
        stream,
        {431, fmt::format("the request head is over the limit of {} bytes", limits_.maxHeadBytes),
         "head"});
    return Next::CloseLingering;
  }
  if (head.status != ConnectionStream::HeadStatus::Complete) return Next::Close;
  const auto checked = checkRequestHead(head.text, limits_);
  if (const auto* error = std::get_if<FramingError>(&checked)) {
    reject(stream, *error);
    return Next::CloseLingering;
  }
  const RequestFraming& framing = std::get<RequestFraming>(checked);
  const std::uint64_t bodyLength = framing.contentLength.value_or(0);
  // Closing is known before the answer for these; httplib then says so in the answer.
  const bool closeAfter =
      last || framing.transferEncoding || (bodyLength > 0 && bodyIgnored(head.text));
  bool connectionClosed = false;
  if (!process_request(stream, closeAfter, connectionClosed, nullptr)) return Next::Close;
  if (closeAfter || connectionClosed) return Next::CloseLingering;
  // A body refused before it was read: its bytes must not become the next request.
  if (stream.bodyBytesRead() < bodyLength) return Next::CloseLingering;
  return Next::KeepOpen;
}

void FramedServer::reject(ConnectionStream& stream, const FramingError& error) {
  Rejection rejection{error, logging::newRequestId(), {}};
  int port = 0;
  stream.get_remote_ip_and_port(rejection.remoteAddress, port);
  const ApiError answer(error.status, errorCode(error.status), error.message, error.field);
  const std::string body = answer.body(rejection.requestId)
                               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
                           "\n";
  const std::string response = fmt::format(
      "HTTP/1.1 {} {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n"
      "Connection: close\r\n{}: {}\r\n\r\n{}",
      error.status, reasonPhrase(error.status), body.size(), kRequestIdHeader, rejection.requestId,
      body);
  for (std::size_t written = 0; written < response.size();) {
    const ssize_t count = stream.write(response.data() + written, response.size() - written);
    if (count <= 0) break;
    written += static_cast<std::size_t>(count);
  }
  logging::event(spdlog::level::info, "request_refused",
                 {{"request_id", rejection.requestId},
                  {"status", error.status},
                  {"field", error.field},
                  {"error", error.message},
                  {"remote", rejection.remoteAddress}});
  if (listener_) listener_(rejection);
}

}  // namespace lghd
