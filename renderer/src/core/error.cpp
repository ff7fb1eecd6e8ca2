#include "lgh/error.hpp"

namespace lgh {

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
