// HTTP/1.1 request framing (RFC 9112), checked on the raw bytes of a request's head (request line,
// header lines, blank line) before httplib parses it. httplib 0.11 is lenient where a proxy in
// front of lghd may not be, and every difference in how two parsers frame the same bytes is a
// request-smuggling hole:
//   - it silently skips a header line that ends in a bare LF, and a line without a colon (an
//     obs-fold continuation), so "Content-Length: 5\n" frames the body for a proxy but not for it;
//   - it keeps whitespace before the colon in the name, so "Content-Length : 5" is not its
//     Content-Length, and percent-decodes header values, so "%35" is its 5;
//   - it takes the first of several Content-Length headers, and ignores Content-Length when
//     Transfer-Encoding is present.
// A head that breaks a rule below is refused with 400 (431 past the size limits, 414 for a long
// request line, 505 for an HTTP version other than 1.0 and 1.1) and the connection is closed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace lghd {

struct FramingLimits {
  std::size_t maxRequestLineBytes = 8192;  // httplib's CPPHTTPLIB_REQUEST_URI_MAX_LENGTH
  std::size_t maxFieldLineBytes = 8192;    // httplib's CPPHTTPLIB_HEADER_MAX_LENGTH
  std::size_t maxFieldLines = 100;
  std::size_t maxHeadBytes = 65536;  // request line + header lines + the blank line
};

// Why a request head was refused: the HTTP status, a message for people, and the header or part
// of the request at fault ("Content-Length", "request-line").
struct FramingError {
  int status = 400;
  std::string message;
  std::string field;
};

// What the framing checks learned about a well-formed head.
struct RequestFraming {
  std::optional<std::uint64_t> contentLength;  // the one Content-Length, when given
  bool transferEncoding = false;  // a (well-formed, chunked-last) Transfer-Encoding is present
  bool http10 = false;
};

// Where the request head at the start of `bytes` ends: one past its first empty line, a line
// ended by LF or by CRLF (so that a bare-LF head is found, and refused, rather than waited for).
// npos when no empty line has come yet.
std::size_t findHeadEnd(std::string_view bytes);

// Checks a complete request head: `head` runs up to and including the CRLF CRLF that ends it.
// Returns the framing, or the reason to refuse the request.
std::variant<RequestFraming, FramingError> checkRequestHead(std::string_view head,
                                                            const FramingLimits& limits);

}  // namespace lghd
