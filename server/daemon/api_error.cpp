#include "api_error.hpp"

namespace lghd {

nlohmann::json ApiError::body(const std::string& requestId) const {
  nlohmann::json error = {{"code", code_},
                          {"message", message_},
                          {"field", field_.empty() ? nlohmann::json() : nlohmann::json(field_)}};
  if (!requestId.empty()) error["request_id"] = requestId;
  return {{"error", std::move(error)}};
}

ApiError fromLghError(const lgh::Error& error) {
  return ApiError(lgh::httpStatus(error.code()), lgh::errorCodeName(error.code()), error.message(),
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
