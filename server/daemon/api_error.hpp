// The daemon's error type: an HTTP status with the JSON body {"error": {code, message, field}}.
// Renderer errors (lgh::Error) convert to it; the daemon adds what only HTTP knows (queue full,
// authentication, unknown routes).
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "lgh/error.hpp"

namespace lghd {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string code, std::string message, std::string field = {})
      : std::runtime_error(message),
        status_(status),
        code_(std::move(code)),
        message_(std::move(message)),
        field_(std::move(field)) {}

  int status() const { return status_; }
  const std::string& code() const { return code_; }
  const std::string& message() const { return message_; }
  const std::string& field() const { return field_; }
  // Seconds for a Retry-After header; 0: none.
  int retryAfterSeconds() const { return retryAfter_; }
  ApiError& withRetryAfter(int seconds) {
    retryAfter_ = seconds;
    return *this;
  }

  // {"error": {"code", "message", "field"}} (field null when empty), plus the request id.
  nlohmann::json body(const std::string& requestId) const;

 private:
  int status_;
  std::string code_;
  std::string message_;
  std::string field_;
  int retryAfter_ = 0;
};

// The HTTP status of a renderer error: 400, 404, 413, 422, 503, 504, 500.
int httpStatus(lgh::ErrorCode code);
ApiError fromLghError(const lgh::Error& error);

// The errors the daemon raises itself, by status.
ApiError badRequest(std::string message, std::string field = {});
ApiError unavailable(std::string message);
ApiError timedOut(std::string message);
ApiError queueFull(std::string message, int retryAfterSeconds);
ApiError internalError(std::string message);

}  // namespace lghd
