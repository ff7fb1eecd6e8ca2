#include "lgh/error.hpp"

namespace lgh {

int httpStatus(ErrorCode code) {
  switch (code) {
    case ErrorCode::BadRequest:
      return 400;
    case ErrorCode::NotFound:
      return 404;
    case ErrorCode::TooLarge:
      return 413;
    case ErrorCode::Invalid:
      return 422;
    case ErrorCode::Unavailable:
      return 503;
    case ErrorCode::Timeout:
      return 504;
    case ErrorCode::Internal:
      return 500;
  }
  return 500;  // a value outside the enum: treat as a bug
}

const char* errorCodeName(ErrorCode code) {
  switch (code) {
    case ErrorCode::BadRequest:
      return "bad_request";
    case ErrorCode::NotFound:
      return "not_found";
    case ErrorCode::TooLarge:
      return "too_large";
    case ErrorCode::Invalid:
      return "invalid";
    case ErrorCode::Unavailable:
      return "unavailable";
    case ErrorCode::Timeout:
      return "timeout";
    case ErrorCode::Internal:
      return "internal";
  }
  return "internal";
}

}  // namespace lgh
