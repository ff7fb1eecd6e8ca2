#include "request/json_text.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "request/json_pointer.hpp"

namespace lgh {
namespace {

using json = nlohmann::json;

// nlohmann's exceptions start with "[json.exception.parse_error.101] parse error at line 1,
// column 4: "; the client wants the part after the position.
std::string withoutExceptionPrefix(std::string_view what) {
  const std::size_t colon = what.find(": ");
  if (colon != std::string_view::npos && what.starts_with("[json.exception.")) {
    what.remove_prefix(colon + 2);
  }
  return std::string(what);
}

// A SAX handler that only keeps track of where in the document the parser is, so that a failure
// can be reported as a JSON Pointer. Used on the error path only: a second pass over bad text.
class PathTracker : public nlohmann::json_sax<json> {
 public:
  struct Failure {
    std::string pointer;
    std::string lastToken;
    int exceptionId = 0;
  };

  const Failure& failure() const { return failure_; }

  bool null() override { return value(); }
  bool boolean(bool /*value*/) override { return value(); }
  bool number_integer(std::int64_t /*value*/) override { return value(); }
  bool number_unsigned(std::uint64_t /*value*/) override { return value(); }
  bool number_float(double /*value*/, const std::string& /*text*/) override { return value(); }
  bool string(std::string& /*value*/) override { return value(); }
  bool binary(json::binary_t& /*value*/) override { return value(); }
  bool start_object(std::size_t /*size*/) override { return open(false); }
  bool key(std::string& name) override {
    frames_.back().key = name;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t /*size*/) override { return open(true); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t /*position*/, const std::string& lastToken,
                   const json::exception& error) override {
    failure_ = {currentPointer(), lastToken, error.id};
    return false;
  }

 private:
  struct Frame {
    bool isArray = false;
    std::size_t index = 0;  // of the next element (arrays)
    std::string key;        // of the current member (objects)
  };

  // A complete value was read: in an array, the next one has the next index.
  bool value() {
    if (!frames_.empty() && frames_.back().isArray) ++frames_.back().index;
    return true;
  }
  bool open(bool isArray) {
    frames_.push_back({isArray, 0, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  std::string currentPointer() const {
    std::vector<std::string> tokens;
    tokens.reserve(frames_.size());
    for (const Frame& frame : frames_) {
      tokens.push_back(frame.isArray ? std::to_string(frame.index) : frame.key);
    }
    return joinPointer(tokens);
  }

  std::vector<Frame> frames_;
  Failure failure_;
};

constexpr int kNumberOverflowId = 406;  // nlohmann's out_of_range.406

[[noreturn]] void throwNumberOverflow(const std::string& text) {
  PathTracker tracker;
  json::sax_parse(text, &tracker);
  const PathTracker::Failure& failure = tracker.failure();
  throw Error(
      ErrorCode::Invalid,
      fmt::format("must be a finite number, got {} (too large for a double)", failure.lastToken),
      failure.pointer.empty() ? "/" : failure.pointer);
}

}  // namespace

json parseRequestJson(const std::string& text) { return parseJsonText(text, kRequestJsonLimits); }

json parseJsonText(const std::string& text, const JsonShapeLimits& shapeLimits) {
  if (const auto excess = findJsonShapeExcess(text, shapeLimits)) {
    throw Error(ErrorCode::TooLarge, "the JSON " + excess->describe(shapeLimits));
  }
  try {
    return json::parse(text);
  } catch (const json::parse_error& error) {
    throw Error(ErrorCode::BadRequest, fmt::format("malformed JSON at byte {}: {}", error.byte,
                                                   withoutExceptionPrefix(error.what())));
  } catch (const json::out_of_range& error) {
    if (error.id == kNumberOverflowId) throwNumberOverflow(text);
    throw Error(ErrorCode::BadRequest,
                fmt::format("malformed JSON: {}", withoutExceptionPrefix(error.what())));
  } catch (const json::exception& error) {
    throw Error(ErrorCode::BadRequest,
                fmt::format("malformed JSON: {}", withoutExceptionPrefix(error.what())));
  }
}

}  // namespace lgh
