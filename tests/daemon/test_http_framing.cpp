// The request-head checks of http_framing.hpp on their own (the HTTP tests send the same attacks
// to the real daemon over a socket).
#include <string>

#include <gtest/gtest.h>

#include "http_framing.hpp"

namespace lghd {
namespace {

std::variant<RequestFraming, FramingError> check(const std::string& head) {
  return checkRequestHead(head, FramingLimits{});
}

FramingError errorOf(const std::string& head) {
  const auto result = check(head);
  if (const auto* error = std::get_if<FramingError>(&result)) return *error;
  ADD_FAILURE() << "accepted: " << head;
  return {};
}

TEST(HttpFraming, WellFormedHeadsGiveTheirFraming) {
  const auto plain = check("GET / HTTP/1.1\r\nHost: a\r\n\r\n");
  ASSERT_TRUE(std::holds_alternative<RequestFraming>(plain));
  EXPECT_FALSE(std::get<RequestFraming>(plain).contentLength);
  const auto post = check("POST /v1/render HTTP/1.1\r\nhost: a\r\ncontent-length:  12 \r\n\r\n");
  ASSERT_TRUE(std::holds_alternative<RequestFraming>(post));
  EXPECT_EQ(std::get<RequestFraming>(post).contentLength, 12U);
  const auto chunked =
      check("POST / HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: gzip, Chunked\r\n\r\n");
  ASSERT_TRUE(std::holds_alternative<RequestFraming>(chunked));
  EXPECT_TRUE(std::get<RequestFraming>(chunked).transferEncoding);
  const auto old = check("GET / HTTP/1.0\r\n\r\n");  // HTTP/1.0 needs no Host
  ASSERT_TRUE(std::holds_alternative<RequestFraming>(old));
  EXPECT_TRUE(std::get<RequestFraming>(old).http10);
}

TEST(HttpFraming, AmbiguousLengthsAreRefused) {
  EXPECT_EQ(
      errorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n").field,
      "Content-Length");
  EXPECT_EQ(
      errorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 1\r\ncontent-length: 1\r\n\r\n").field,
      "Content-Length");
  EXPECT_EQ(errorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 1, 1\r\n\r\n").field,
            "Content-Length");
  EXPECT_EQ(errorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 0x10\r\n\r\n").field,
            "Content-Length");
  EXPECT_EQ(
      errorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 1234567890123456789\r\n\r\n").field,
      "Content-Length");
  EXPECT_EQ(errorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 3\r\n"
                    "Transfer-Encoding: chunked\r\n\r\n")
                .field,
            "Transfer-Encoding");
  EXPECT_EQ(errorOf("POST / HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: chunked, gzip\r\n\r\n").field,
            "Transfer-Encoding");
  EXPECT_EQ(errorOf("POST / HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: xchunked\r\n\r\n").field,
            "Transfer-Encoding");
  EXPECT_EQ(errorOf("POST / HTTP/1.0\r\nTransfer-Encoding: chunked\r\n\r\n").field,
            "Transfer-Encoding");
}

TEST(HttpFraming, MalformedLinesAreRefused) {
  EXPECT_EQ(errorOf("GET / HTTP/1.1\nHost: a\r\n\r\n").field, "head");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nX: 1\n\r\n").field, "head");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nX: 1\r\n\tfolded\r\n\r\n").field, "head");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nContent-Length : 1\r\n\r\n").field,
            "Content-Length");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nBad Name: 1\r\n\r\n").field, "head");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nNoColon\r\n\r\n").field, "head");
  EXPECT_EQ(errorOf("GET  / HTTP/1.1\r\nHost: a\r\n\r\n").field, "request-line");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n").field, "Host");
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\n\r\n").field, "Host");
  EXPECT_EQ(errorOf("GET / HTTP/3.0\r\nHost: a\r\n\r\n").status, 505);
  EXPECT_EQ(errorOf("GET / HTTP/1.1\r\nHost: a\r\nX: \x01\r\n\r\n").field, "X");
}

TEST(HttpFraming, SizeLimitsAre431And414) {
  FramingLimits limits;
  limits.maxFieldLines = 2;
  const auto many = checkRequestHead("GET / HTTP/1.1\r\nHost: a\r\nA: 1\r\nB: 2\r\n\r\n", limits);
  EXPECT_EQ(std::get<FramingError>(many).status, 431);
  EXPECT_EQ(
      errorOf("GET / HTTP/1.1\r\nHost: a\r\nX: " + std::string(9000, 'x') + "\r\n\r\n").status,
      431);
  EXPECT_EQ(errorOf("GET /" + std::string(9000, 'x') + " HTTP/1.1\r\nHost: a\r\n\r\n").status, 414);
}

TEST(HttpFraming, HeadEndIsTheFirstEmptyLine) {
  EXPECT_EQ(findHeadEnd("GET / HTTP/1.1\r\nHost: a\r\n\r\nBODY"), 27U);
  EXPECT_EQ(findHeadEnd("GET / HTTP/1.1\nHost: a\n\nBODY"), 24U);  // found, then refused
  EXPECT_EQ(findHeadEnd("GET / HTTP/1.1\r\nHost: a\r\n"), std::string_view::npos);
}

}  // namespace
}  // namespace lghd
