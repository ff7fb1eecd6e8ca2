#include "http_conventions.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>

#include <fmt/format.h>

#include "http_util.hpp"

namespace lghd {
namespace {

constexpr std::string_view kJson = "application/json";

// --- Route table --------------------------------------------------------------------------------

std::vector<std::string_view> segments(std::string_view path) {
  std::vector<std::string_view> parts;
  std::size_t start = 1;  // past the leading '/'
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::size_t end = slash == std::string_view::npos ? path.size() : slash;
    parts.push_back(path.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

bool isSchemaFileName(std::string_view name) {
  constexpr std::string_view kSuffix = ".schema.json";
  if (name.size() <= kSuffix.size() || !name.ends_with(kSuffix)) return false;
  return std::all_of(
      name.begin(), name.end() - static_cast<std::ptrdiff_t>(kSuffix.size()),
      [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-'; });
}

bool segmentMatches(std::string_view pattern, std::string_view segment) {
  if (!pattern.starts_with('{')) return pattern == segment;
  if (pattern == "{schema}") return isSchemaFileName(segment);
  return !segment.empty();
}

bool pathMatches(std::string_view pattern, const std::string& path) {
  if (!path.starts_with('/')) return false;
  const std::vector<std::string_view> want = segments(pattern);
  const std::vector<std::string_view> got = segments(path);
  if (want.size() != got.size()) return false;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (!segmentMatches(want[i], got[i])) return false;
  }
  return true;
}

bool allows(const RouteSpec& route, std::string_view method) {
  const auto& methods = route.methods;
  if (std::find(methods.begin(), methods.end(), method) != methods.end()) return true;
  return method == "HEAD" && std::find(methods.begin(), methods.end(), "GET") != methods.end();
}

// --- Accept -------------------------------------------------------------------------------------

struct MediaRange {
  std::string type;     // "image", or "*"
  std::string subtype;  // "png", or "*"
  double q = 1.0;
  std::size_t index = 0;  // position in the header
};

std::string trimmed(std::string_view text) {
  const auto begin = text.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return {};
  const auto end = text.find_last_not_of(" \t");
  return std::string(text.substr(begin, end - begin + 1));
}

std::string lowercase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// "q=0.5" -> 0.5; nullopt when the value is not a qvalue (RFC 9110: 0 to 1, three decimals).
std::optional<double> qValue(std::string_view value) {
  if (value.empty() || value.size() > 5) return std::nullopt;
  const std::string text(value);
  char* end = nullptr;
  const double q = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || q < 0.0 || q > 1.0) return std::nullopt;
  return q;
}

// A range with a malformed q-value is left out, as if the client had not sent it.
std::optional<MediaRange> parseRange(std::string_view text, std::size_t index) {
  std::size_t semicolon = text.find(';');
  const std::string type = lowercase(trimmed(text.substr(0, semicolon)));
  const std::size_t slash = type.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == type.size()) return std::nullopt;
  MediaRange range{type.substr(0, slash), type.substr(slash + 1), 1.0, index};
  if (range.type == "*" && range.subtype != "*") return std::nullopt;
  while (semicolon != std::string_view::npos) {
    const std::size_t next = text.find(';', semicolon + 1);
    const std::string parameter = trimmed(text.substr(semicolon + 1, next - semicolon - 1));
    if (parameter.size() > 2 && (parameter[0] == 'q' || parameter[0] == 'Q') &&
        parameter[1] == '=') {
      const std::optional<double> q = qValue(std::string_view(parameter).substr(2));
      if (!q) return std::nullopt;
      range.q = *q;
    }
    semicolon = next;
  }
  return range;
}

std::vector<MediaRange> parseAccept(const std::string& accept) {
  std::vector<MediaRange> ranges;
  std::size_t start = 0;
  while (start <= accept.size()) {
    const std::size_t comma = accept.find(',', start);
    const std::size_t end = comma == std::string::npos ? accept.size() : comma;
    if (auto range =
            parseRange(std::string_view(accept).substr(start, end - start), ranges.size())) {
      ranges.push_back(std::move(*range));
    }
    start = end + 1;
  }
  return ranges;
}

// 2: type/subtype, 1: type/*, 0: */*, -1: no match.
int specificity(const MediaRange& range, std::string_view type, std::string_view subtype) {
  if (range.type == "*") return 0;
  if (range.type != type) return -1;
  if (range.subtype == "*") return 1;
  return range.subtype == subtype ? 2 : -1;
}

struct Preference {
  double q = 0.0;
  int specificity = -1;
  std::size_t rangeIndex = 0;
  std::size_t offerIndex = 0;
};

// The range that decides about `offer`: the most specific one that matches it.
std::optional<Preference> preferenceFor(const std::vector<MediaRange>& ranges,
                                        std::string_view offer, std::size_t offerIndex) {
  const std::string media = lowercase(std::string(offer.substr(0, offer.find(';'))));
  const std::size_t slash = media.find('/');
  const std::string_view type = std::string_view(media).substr(0, slash);
  const std::string_view subtype = std::string_view(media).substr(slash + 1);
  std::optional<Preference> best;
  for (const MediaRange& range : ranges) {
    const int s = specificity(range, type, subtype);
    if (s < 0) continue;
    if (!best || s > best->specificity) best = Preference{range.q, s, range.index, offerIndex};
  }
  return best;
}

bool preferred(const Preference& a, const Preference& b) {
  if (a.q != b.q) return a.q > b.q;
  if (a.specificity != b.specificity) return a.specificity > b.specificity;
  if (a.rangeIndex != b.rangeIndex) return a.rangeIndex < b.rangeIndex;
  return a.offerIndex < b.offerIndex;
}

// --- CORS ---------------------------------------------------------------------------------------

constexpr const char* kExposedHeaders =
    "X-Request-Id, Location, Retry-After, Server-Timing, X-Lgh-Timings, X-Lgh-Render-Ms, "
    "X-Lgh-Queue-Ms, X-Lgh-Cache, X-Lgh-Renderer, X-Lgh-Context, X-Lgh-Paths, X-Lgh-Warnings, "
    "X-Lgh-Thumbnails-Ok, X-Lgh-Thumbnails-Failed";
constexpr const char* kAllowedRequestHeaders =
    "Authorization, Content-Type, Accept, X-Request-Id, X-Lgh-Deadline-Ms";
constexpr int kPreflightMaxAgeSeconds = 600;

bool originAllowed(const std::vector<std::string>& origins, const std::string& origin) {
  if (origin.empty()) return false;
  return std::any_of(origins.begin(), origins.end(), [&](const std::string& allowed) {
    return allowed == "*" || allowed == origin;
  });
}

bool anyOrigin(const std::vector<std::string>& origins) {
  return std::find(origins.begin(), origins.end(), "*") != origins.end();
}

void addCorsHeaders(const std::vector<std::string>& origins, const std::string& origin,
                    httplib::Response& response) {
  response.set_header("Access-Control-Allow-Origin", anyOrigin(origins) ? "*" : origin);
  if (!anyOrigin(origins)) response.set_header("Vary", "Origin");
  response.set_header("Access-Control-Expose-Headers", kExposedHeaders);
}

// Every body-carrying answer given before httplib read the body closes the connection: the
// unread body would otherwise be taken for the next request.
void closeIfBodyUnread(const httplib::Request& request, httplib::Response& response) {
  if (request.get_header_value<std::uint64_t>("Content-Length") > 0) {
    response.set_header("Connection", "close");
  }
}

}  // namespace

const std::vector<RouteSpec>& routeTable() {
  static const std::vector<RouteSpec> routes = {
      {"/v1/render", {"POST"}, {}},          {"/v1/thumbnails", {"POST"}, {}},
      {"/v1/jobs", {"POST"}, {kJson}},       {"/v1/jobs/{id}", {"GET", "DELETE"}, {kJson}},
      {"/v1/jobs/{id}/result", {"GET"}, {}}, {"/v1/info", {"GET"}, {kJson}},
      {"/healthz", {"GET"}, {kJson}},        {"/readyz", {"GET"}, {kJson}},
      {"/metrics", {"GET"}, {"text/plain"}}, {"/openapi.json", {"GET"}, {kJson}},
      {"/v1/benchmark", {"POST", "GET"}, {kJson}}, {"/v1/benchmark/result", {"GET"}, {kJson}},
      {"/{schema}", {"GET"}, {kJson}},       {"/proto/{schema}", {"GET"}, {kJson}},
  };
  return routes;
}

const RouteSpec* matchRoute(const std::string& path) {
  for (const RouteSpec& route : routeTable()) {
    if (pathMatches(route.path, path)) return &route;
  }
  return nullptr;
}

std::string allowHeader(const RouteSpec& route) {
  std::string allow;
  for (std::string_view method : route.methods) {
    if (!allow.empty()) allow += ", ";
    allow += method;
    if (method == "GET") allow += ", HEAD";
  }
  return allow + ", OPTIONS";
}

std::optional<std::string> negotiate(const std::string& accept,
                                     const std::vector<std::string_view>& offers) {
  if (offers.empty()) return std::nullopt;
  if (trimmed(accept).empty()) return std::string(offers.front());
  const std::vector<MediaRange> ranges = parseAccept(accept);
  if (ranges.empty()) return std::string(offers.front());  // nothing parsable: as if absent
  std::optional<Preference> best;
  for (std::size_t i = 0; i < offers.size(); ++i) {
    const std::optional<Preference> preference = preferenceFor(ranges, offers[i], i);
    if (!preference || preference->q <= 0.0) continue;
    if (!best || preferred(*preference, *best)) best = preference;
  }
  if (!best) return std::nullopt;
  return std::string(offers[best->offerIndex]);
}

std::string chooseMediaType(const httplib::Request& request,
                            const std::vector<std::string_view>& offers) {
  const std::string accept = request.get_header_value("Accept");
  if (std::optional<std::string> chosen = negotiate(accept, offers)) return *chosen;
  std::string list;
  for (std::string_view offer : offers) list += (list.empty() ? "" : ", ") + std::string(offer);
  throw ApiError(406, "not_acceptable",
                 fmt::format("this answer is {}; the Accept header allows none of them", list),
                 "Accept");
}

bool answeredCorsOrOptions(const std::vector<std::string>& corsOrigins,
                           const httplib::Request& request, httplib::Response& response) {
  const std::string origin = request.get_header_value("Origin");
  const bool corsOrigin = originAllowed(corsOrigins, origin);
  if (corsOrigin) addCorsHeaders(corsOrigins, origin, response);
  if (request.method != "OPTIONS") return false;
  const RouteSpec* route = matchRoute(request.path);
  if (route == nullptr) return false;  // 404 as for any method
  const std::string allow = allowHeader(*route);
  response.status = 204;
  response.set_header("Allow", allow);
  const bool preflight = request.has_header("Access-Control-Request-Method");
  if (corsOrigin && preflight) {
    response.set_header("Access-Control-Allow-Methods", allow);
    response.set_header("Access-Control-Allow-Headers", kAllowedRequestHeaders);
    response.set_header("Access-Control-Max-Age", std::to_string(kPreflightMaxAgeSeconds));
  }
  closeIfBodyUnread(request, response);
  return true;
}

bool refusedMethodOrMediaType(const httplib::Request& request, httplib::Response& response) {
  const RouteSpec* route = matchRoute(request.path);
  if (route == nullptr) return false;
  if (!allows(*route, request.method)) {
    response.set_header("Allow", allowHeader(*route));
    closeIfBodyUnread(request, response);
    sendError(response, ApiError(405, "method_not_allowed",
                                 fmt::format("{} does not take {}; it takes {}", route->path,
                                             request.method, allowHeader(*route)),
                                 "method"));
    return true;
  }
  if (route->offers.empty()) return false;
  try {
    chooseMediaType(request, route->offers);
  } catch (const ApiError& error) {
    closeIfBodyUnread(request, response);
    sendError(response, error);
    return true;
  }
  return false;
}

}  // namespace lghd
