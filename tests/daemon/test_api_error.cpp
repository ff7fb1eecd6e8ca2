// api_error.hpp: the HTTP status of every renderer error code, and the JSON error body the daemon
// answers with ({"error": {code, message, field, request_id}}).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "api_error.hpp"
#include "lgh/error.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;

TEST(HttpStatus, OfEveryErrorCode) {
  const std::vector<std::pair<lgh::ErrorCode, int>> expected{
      {lgh::ErrorCode::BadRequest, 400},  {lgh::ErrorCode::NotFound, 404},
      {lgh::ErrorCode::TooLarge, 413},    {lgh::ErrorCode::Invalid, 422},
      {lgh::ErrorCode::Unavailable, 503}, {lgh::ErrorCode::Timeout, 504},
      {lgh::ErrorCode::Internal, 500},
  };
  for (const auto& [code, status] : expected) {
    EXPECT_EQ(httpStatus(code), status) << lgh::errorCodeName(code);
  }
}

TEST(HttpStatus, ValueOutsideTheEnumIsInternal) {
  EXPECT_EQ(httpStatus(static_cast<lgh::ErrorCode>(1000)), 500);
}

TEST(ApiError, FromRendererErrorKeepsCodeMessageAndField) {
  const ApiError error =
      fromLghError(lgh::Error(lgh::ErrorCode::TooLarge, "over the limit", "/output/width"));
  EXPECT_EQ(error.status(), 413);
  EXPECT_EQ(error.code(), "too_large");
  EXPECT_EQ(error.message(), "over the limit");
  EXPECT_EQ(error.field(), "/output/width");
  EXPECT_STREQ(error.what(), "over the limit");
  EXPECT_EQ(error.retryAfterSeconds(), 0);
}

TEST(ApiError, BodyWithFieldAndRequestId) {
  const ApiError error = badRequest("must be a number", "/output/width");
  EXPECT_EQ(error.body("abc123"), json::parse(R"({"error": {"code": "bad_request",
      "message": "must be a number", "field": "/output/width", "request_id": "abc123"}})"));
}

TEST(ApiError, BodyWithoutFieldHasNullFieldAndNoRequestId) {
  const json body = internalError("boom").body("");
  EXPECT_EQ(body, json::parse(R"({"error": {"code": "internal", "message": "boom",
      "field": null}})"));
}

TEST(ApiError, DaemonErrorsByStatus) {
  struct Case {
    ApiError error;
    int status;
    std::string code;
  };
  const std::vector<Case> cases{
      {badRequest("b"), 400, "bad_request"},  {unavailable("u"), 503, "unavailable"},
      {timedOut("t"), 504, "timeout"},        {internalError("i"), 500, "internal"},
      {queueFull("q", 3), 429, "queue_full"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(c.error.status(), c.status) << c.code;
    EXPECT_EQ(c.error.code(), c.code);
    EXPECT_TRUE(c.error.field().empty()) << c.code;
  }
}

TEST(ApiError, QueueFullCarriesRetryAfter) {
  const ApiError error = queueFull("the render queue is full (4 waiting)", 7);
  EXPECT_EQ(error.retryAfterSeconds(), 7);
  EXPECT_EQ(error.message(), "the render queue is full (4 waiting)");
  ApiError starting = unavailable("starting");
  EXPECT_EQ(starting.retryAfterSeconds(), 0);
  EXPECT_EQ(starting.withRetryAfter(1).retryAfterSeconds(), 1);
}

}  // namespace
}  // namespace lghd
