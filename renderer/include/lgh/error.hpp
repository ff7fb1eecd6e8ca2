// One error type for everything a caller can get wrong or the renderer can fail at. The daemon
// maps `code` to an HTTP status (server/daemon/api_error.cpp); the CLI prints `what()` on one line.
#pragma once

#include <stdexcept>
#include <string>

namespace lgh {

enum class ErrorCode {
  BadRequest,   // 400: malformed input (not JSON, wrong type, schema violation)
  NotFound,     // 404: an asset or file that does not exist
  TooLarge,     // 413: over a configured size limit
  Invalid,      // 422: well-formed but semantically invalid (NaN, limits, broken glTF)
  Unavailable,  // 503: no usable device or context
  Timeout,      // 504: the render ran past its deadline
  Internal,     // 500: a bug or a driver failure
};

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, std::string message, std::string field = {})
      : std::runtime_error(field.empty() ? message : field + ": " + message),
        code_(code),
        message_(std::move(message)),
        field_(std::move(field)) {}

  ErrorCode code() const { return code_; }
  // The message without the field prefix.
  const std::string& message() const { return message_; }
  // JSON path (e.g. "/camera/position/1") or file name the error is about; may be empty.
  const std::string& field() const { return field_; }

 private:
  ErrorCode code_;
  std::string message_;
  std::string field_;
};

// "bad_request", "not_found", ...: the `code` of the daemon's JSON errors and the CLI's messages.
const char* errorCodeName(ErrorCode code);

}  // namespace lgh
