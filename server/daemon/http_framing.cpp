#include "http_framing.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

#include <fmt/format.h>

namespace lghd {
namespace {

using Result = std::variant<RequestFraming, FramingError>;

FramingError badRequest(std::string message, std::string field) {
  return {400, std::move(message), std::move(field)};
}

// RFC 9110 token characters (method and field names).
bool isTokenChar(unsigned char c) {
  if (std::isalnum(c) != 0) return true;
  static constexpr std::string_view kSymbols = "!#$%&'*+-.^_`|~";
  return kSymbols.find(static_cast<char>(c)) != std::string_view::npos;
}

bool isToken(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return isTokenChar(static_cast<unsigned char>(c));
  });
}

bool isWhitespace(char c) { return c == ' ' || c == '\t'; }

// Field values: visible ASCII, obs-text, and space or tab between them.
bool isFieldValueChar(unsigned char c) { return c == '\t' || (c >= 0x20 && c != 0x7F); }

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && isWhitespace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isWhitespace(text.back())) text.remove_suffix(1);
  return text;
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// A printable rendering of a few bytes of the request for messages (which end up in JSON).
std::string quoted(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 40)) {
    const auto byte = static_cast<unsigned char>(c);
    out += byte >= 0x20 && byte < 0x7F ? std::string(1, c) : fmt::format("\\x{:02x}", byte);
  }
  return text.size() > 40 ? out + "..." : out;
}

// The head cut into lines, each checked to end in CRLF and to hold no other CR or LF.
struct Lines {
  std::vector<std::string_view> lines;  // without their CRLF; the last is the empty line
  std::optional<FramingError> error;
};

Lines splitLines(std::string_view head) {
  Lines result;
  std::size_t start = 0;
  while (start < head.size()) {
    const std::size_t lf = head.find('\n', start);
    if (lf == std::string_view::npos) {
      result.error = badRequest("the request head does not end with an empty line", "head");
      return result;
    }
    if (lf == start || head[lf - 1] != '\r') {
      result.error = badRequest(
          fmt::format("bare LF at byte {}: every line of the request head must end in CRLF", lf),
          "head");
      return result;
    }
    const std::string_view line = head.substr(start, lf - 1 - start);
    if (const std::size_t cr = line.find('\r'); cr != std::string_view::npos) {
      result.error = badRequest(
          fmt::format("bare CR at byte {}: CR is allowed only before LF", start + cr), "head");
      return result;
    }
    result.lines.push_back(line);
    start = lf + 1;
    if (line.empty()) break;
  }
  if (start != head.size() || result.lines.empty() || !result.lines.back().empty()) {
    result.error = badRequest("the request head does not end with an empty line", "head");
  }
  return result;
}

std::optional<FramingError> checkRequestLine(std::string_view line, const FramingLimits& limits,
                                             RequestFraming& framing) {
  if (line.size() > limits.maxRequestLineBytes) {
    return FramingError{414,
                        fmt::format("the request line is {} bytes, over the limit of {}",
                                    line.size(), limits.maxRequestLineBytes),
                        "request-line"};
  }
  const std::size_t firstSpace = line.find(' ');
  const std::size_t lastSpace = line.rfind(' ');
  if (firstSpace == std::string_view::npos || firstSpace == lastSpace) {
    return badRequest(fmt::format("malformed request line '{}': expected METHOD SP TARGET SP "
                                  "HTTP-VERSION",
                                  quoted(line)),
                      "request-line");
  }
  const std::string_view method = line.substr(0, firstSpace);
  const std::string_view target = line.substr(firstSpace + 1, lastSpace - firstSpace - 1);
  const std::string_view version = line.substr(lastSpace + 1);
  const bool targetOk = !target.empty() && std::all_of(target.begin(), target.end(),
                                                       [](char c) { return c > 0x20 && c < 0x7F; });
  if (!isToken(method) || !targetOk) {
    return badRequest(fmt::format("malformed request line '{}': expected METHOD SP TARGET SP "
                                  "HTTP-VERSION, single spaces, no control characters",
                                  quoted(line)),
                      "request-line");
  }
  if (version == "HTTP/1.1" || version == "HTTP/1.0") {
    framing.http10 = version == "HTTP/1.0";
    return std::nullopt;
  }
  const bool versionShaped = version.size() == 8 && version.starts_with("HTTP/") &&
                             std::isdigit(static_cast<unsigned char>(version[5])) != 0 &&
                             version[6] == '.' &&
                             std::isdigit(static_cast<unsigned char>(version[7])) != 0;
  if (versionShaped) {
    return FramingError{505, fmt::format("{} is not supported: HTTP/1.1 or HTTP/1.0", version),
                        "request-line"};
  }
  return badRequest(fmt::format("malformed HTTP version '{}'", quoted(version)), "request-line");
}

struct Field {
  std::string_view name;
  std::string_view value;
};

std::variant<Field, FramingError> parseFieldLine(std::string_view line,
                                                 const FramingLimits& limits) {
  if (line.size() > limits.maxFieldLineBytes) {
    return FramingError{431,
                        fmt::format("a header line is {} bytes, over the limit of {}", line.size(),
                                    limits.maxFieldLineBytes),
                        std::string(line.substr(0, std::min<std::size_t>(line.find(':'), 64)))};
  }
  if (isWhitespace(line.front())) {
    return badRequest(fmt::format("obsolete line folding (a header line starting with "
                                  "whitespace: '{}') is not accepted",
                                  quoted(line)),
                      "head");
  }
  const std::size_t colon = line.find(':');
  if (colon == std::string_view::npos) {
    return badRequest(fmt::format("header line '{}' has no colon", quoted(line)), "head");
  }
  const std::string_view name = line.substr(0, colon);
  if (isWhitespace(name.back())) {
    return badRequest(
        fmt::format("whitespace between the header name '{}' and its colon", quoted(trimmed(name))),
        std::string(trimmed(name)));
  }
  if (!isToken(name)) {
    return badRequest(fmt::format("'{}' is not a valid header name", quoted(name)), "head");
  }
  const std::string_view value = trimmed(line.substr(colon + 1));
  for (char c : value) {
    if (!isFieldValueChar(static_cast<unsigned char>(c))) {
      return badRequest(fmt::format("the value of header {} holds the control character 0x{:02x}",
                                    name, static_cast<unsigned char>(c)),
                        std::string(name));
    }
  }
  return Field{name, value};
}

std::variant<std::uint64_t, FramingError> parseContentLength(
    const std::vector<std::string_view>& values) {
  if (values.size() > 1) {
    return badRequest(fmt::format("Content-Length is given {} times; a request carries exactly "
                                  "one",
                                  values.size()),
                      "Content-Length");
  }
  const std::string_view value = values.front();
  const bool digits = !value.empty() && std::all_of(value.begin(), value.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (!digits || value.size() > 18) {
    return badRequest(fmt::format("Content-Length must be a decimal number of bytes (at most 18 "
                                  "digits), got '{}'",
                                  quoted(value)),
                      "Content-Length");
  }
  std::uint64_t length = 0;
  for (char c : value) length = length * 10 + static_cast<std::uint64_t>(c - '0');
  return length;
}

// Transfer-Encoding: a list over one or more lines whose last coding must be chunked (RFC 9112
// 6.3, rule 4), with chunked at most once.
std::optional<FramingError> checkTransferEncoding(const std::vector<std::string_view>& values) {
  std::vector<std::string_view> codings;
  for (std::string_view value : values) {
    std::size_t start = 0;
    while (start <= value.size()) {
      const std::size_t comma = std::min(value.find(',', start), value.size());
      const std::string_view coding = trimmed(value.substr(start, comma - start));
      if (!coding.empty()) codings.push_back(coding);
      start = comma + 1;
    }
  }
  const auto chunked = std::count_if(codings.begin(), codings.end(), [](std::string_view coding) {
    return equalsIgnoringCase(coding, "chunked");
  });
  if (codings.empty() || !equalsIgnoringCase(codings.back(), "chunked") || chunked != 1) {
    return badRequest(
        "Transfer-Encoding must end with chunked, once, or the body length cannot be "
        "determined",
        "Transfer-Encoding");
  }
  return std::nullopt;
}

std::optional<FramingError> checkFraming(const std::vector<Field>& fields,
                                         RequestFraming& framing) {
  std::vector<std::string_view> contentLengths;
  std::vector<std::string_view> transferEncodings;
  std::size_t hosts = 0;
  for (const Field& field : fields) {
    if (equalsIgnoringCase(field.name, "Content-Length")) contentLengths.push_back(field.value);
    if (equalsIgnoringCase(field.name, "Transfer-Encoding")) {
      transferEncodings.push_back(field.value);
    }
    if (equalsIgnoringCase(field.name, "Host")) ++hosts;
  }
  if (hosts > 1) return badRequest("Host is given more than once", "Host");
  if (hosts == 0 && !framing.http10) return badRequest("an HTTP/1.1 request needs a Host", "Host");
  if (!transferEncodings.empty()) {
    if (!contentLengths.empty()) {
      return badRequest(
          "Content-Length and Transfer-Encoding together: the body length is "
          "ambiguous",
          "Transfer-Encoding");
    }
    if (framing.http10) {
      return badRequest("Transfer-Encoding is not part of HTTP/1.0", "Transfer-Encoding");
    }
    if (auto error = checkTransferEncoding(transferEncodings)) return error;
    framing.transferEncoding = true;
  }
  if (!contentLengths.empty()) {
    auto length = parseContentLength(contentLengths);
    if (auto* error = std::get_if<FramingError>(&length)) return *error;
    framing.contentLength = std::get<std::uint64_t>(length);
  }
  return std::nullopt;
}

}  // namespace

std::size_t findHeadEnd(std::string_view bytes) {
  for (std::size_t lf = bytes.find('\n'); lf != std::string_view::npos;
       lf = bytes.find('\n', lf + 1)) {
    if (lf + 1 < bytes.size() && bytes[lf + 1] == '\n') return lf + 2;
    if (lf + 2 < bytes.size() && bytes[lf + 1] == '\r' && bytes[lf + 2] == '\n') return lf + 3;
  }
  return std::string_view::npos;
}

std::variant<RequestFraming, FramingError> checkRequestHead(std::string_view head,
                                                            const FramingLimits& limits) {
  if (head.size() > limits.maxHeadBytes) {
    return FramingError{431,
                        fmt::format("the request head is {} bytes, over the limit of {}",
                                    head.size(), limits.maxHeadBytes),
                        "head"};
  }
  const Lines split = splitLines(head);
  if (split.error) return *split.error;
  const std::vector<std::string_view>& lines = split.lines;
  if (lines.size() < 2) return badRequest("the request line is empty", "request-line");
  RequestFraming framing;
  if (auto error = checkRequestLine(lines.front(), limits, framing)) return *error;
  const std::size_t fieldLines = lines.size() - 2;  // minus the request line and the empty line
  if (fieldLines > limits.maxFieldLines) {
    return FramingError{431,
                        fmt::format("the request has {} header lines, over the limit of {}",
                                    fieldLines, limits.maxFieldLines),
                        "head"};
  }
  std::vector<Field> fields;
  fields.reserve(fieldLines);
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    auto field = parseFieldLine(lines[i], limits);
    if (auto* error = std::get_if<FramingError>(&field)) return *error;
    fields.push_back(std::get<Field>(field));
  }
  if (auto error = checkFraming(fields, framing)) return *error;
  return framing;
}

}  // namespace lghd
