// Small pieces every route uses: JSON and error answers, the request id, the deadline, and a
// wrapper that turns any exception of a handler into the JSON error body.
#pragma once

#include <functional>
#include <string>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "api_error.hpp"
#include "config.hpp"
#include "render_ticket.hpp"

namespace lghd {

inline constexpr const char* kRequestIdHeader = "X-Request-Id";

// The request id the pre-routing handler put on the response.
std::string requestIdOf(const httplib::Response& response);

void sendJson(httplib::Response& response, int status, const nlohmann::json& body);
void sendError(httplib::Response& response, const ApiError& error);

// The JSON body; an empty body is {}. Throws lgh::Error (lgh::parseRequestJson): 400 naming the
// byte of a syntax error, 413 past the nesting or value limits of request JSON.
nlohmann::json parseJsonBody(const std::string& body);

// The request's deadline: now + the configured deadline, or sooner when the client's
// X-Lgh-Deadline-Ms header asks for less. Throws ApiError 400 for a malformed header.
Clock::time_point deadlineFor(const httplib::Request& request, const DaemonConfig& config);

// A header value safe to send: control characters replaced, length bounded.
std::string headerSafe(const std::string& value);

using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;
// Runs `handler`; ApiError, lgh::Error and any other exception become JSON error answers (the
// last as a logged 500 carrying the request id).
Handler guarded(Handler handler);

}  // namespace lghd
