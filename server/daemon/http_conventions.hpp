// HTTP conventions every route follows, in one place: the route table (paths and methods, the
// source of 405 + Allow and of bounded metric labels), content negotiation on Accept (q-values,
// 406), and CORS for browser clients (--cors-origin; preflights answered before authentication).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <httplib.h>

namespace lghd {

struct RouteSpec {
  // The OpenAPI path template: "/v1/jobs/{id}". A parameter matches one path segment; one named
  // {schema} matches only a proto schema's file name ("render-request.schema.json").
  std::string_view path;
  std::vector<std::string_view>
      methods;  // GET implies HEAD (httplib answers HEAD with GET's handler)
  // What the route answers, for 406 before any work is done; empty when the route negotiates
  // itself (the media type depends on the request body or the job).
  std::vector<std::string_view> offers;
};

// Every route of the daemon. tests/daemon/test_contract.cpp checks it against proto/openapi.json.
const std::vector<RouteSpec>& routeTable();

// The route `path` matches, or nullptr.
const RouteSpec* matchRoute(const std::string& path);

// The Allow header of a route: its methods, HEAD after GET, and OPTIONS.
std::string allowHeader(const RouteSpec& route);

// --- Content negotiation ------------------------------------------------------------------------

// The offer (a media type such as "image/png") the Accept header prefers, as proactive
// negotiation does (RFC 9110 section 12.5.1): the highest q-value wins, then the more specific
// media range (type/subtype over type/* over */*), then the range the client listed first, then
// the order of `offers`. Ranges with q=0 exclude a type. No Accept header (or an empty one)
// accepts anything: the first offer. nullopt when nothing offered is acceptable (answer 406).
std::optional<std::string> negotiate(const std::string& accept,
                                     const std::vector<std::string_view>& offers);

// negotiate() with the request's Accept header; throws ApiError 406 (not_acceptable) naming the
// offers when none is acceptable.
std::string chooseMediaType(const httplib::Request& request,
                            const std::vector<std::string_view>& offers);

// --- The pre-routing checks
// -----------------------------------------------------------------------

// Adds the CORS answer headers when the request's Origin is in `corsOrigins` (--cors-origin;
// empty: no CORS, "*": any origin) to every answer, errors too,
// so that a browser can read them). Returns true when the request was a preflight (OPTIONS with
// Access-Control-Request-Method) or a plain OPTIONS, which it answered (204): these need no
// authentication.
bool answeredCorsOrOptions(const std::vector<std::string>& corsOrigins,
                           const httplib::Request& request, httplib::Response& response);

// 405 with Allow for a known route asked with another method, and 406 for a route of fixed media
// types whose Accept excludes them. Returns true when it answered.
bool refusedMethodOrMediaType(const httplib::Request& request, httplib::Response& response);

}  // namespace lghd
