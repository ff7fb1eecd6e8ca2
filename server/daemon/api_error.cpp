#include "api_error.hpp"

namespace lghd {

nlohmann::json ApiError::body(const std::string& requestId) const {
  nlohmann::json error = {{"code", code_},
                          {"message", message_},
                          {"field", field_.empty() ? nlohmann::json() : nlohmann::json(field_)}};
  if (!requestId.empty()) error["request_id"] = requestId;
  return {{"error", std::move(error)}};
}

int httpStatus(lgh::ErrorCode code) {
  switch (code) {
    case lgh::ErrorCode::BadRequest:
      return 400;
    case lgh::ErrorCode::NotFound:
      return 404;
    case lgh::ErrorCode::TooLarge:
      return 413;
    case lgh::ErrorCode::Invalid:
      return 422;
    case lgh::ErrorCode::Unavailable:
      return 503;
    case lgh::ErrorCode::Timeout:
      return 504;
    case lgh::ErrorCode::Internal:
      return 500;
  }
  return 500;  // a value outside the enum: treat as a bug
}

ApiError fromLghError(const lgh::Error& error) {
  return ApiError(httpStatus(error.code()), lgh::errorCodeName(error.code()), error.message(),
                  error.field());
}

ApiError badRequest(std::string message, std::string field) {
  return fromLghError(lgh::Error(lgh::ErrorCode::BadRequest, std::move(message), std::move(field)));
}

ApiError unavailable(std::string message) {
  return fromLghError(lgh::Error(lgh::ErrorCode::Unavailable, std::move(message)));
}

ApiError timedOut(std::string message) {
  return fromLghError(lgh::Error(lgh::ErrorCode::Timeout, std::move(message)));
}

ApiError queueFull(std::string message, int retryAfterSeconds) {
  return ApiError(429, "queue_full", std::move(message)).withRetryAfter(retryAfterSeconds);
}

ApiError internalError(std::string message) {
  return fromLghError(lgh::Error(lgh::ErrorCode::Internal, std::move(message)));
}

}  // namespace lghd
