#include "request/schema_validation.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "request/json_pointer.hpp"
#include "request/schema_bundle.hpp"
#include "request/schema_lookup.hpp"
#include "request/valijson_include.hpp"

namespace lgh {
namespace {

using json = nlohmann::json;
using Nodes = std::vector<const json*>;

// A proto schema, bundled and compiled once per process. valijson only reads the Schema while
// validating, so threads can share it (each call makes its own Validator).
struct CompiledSchema {
  json bundle;
  valijson::Schema schema;

  explicit CompiledSchema(const std::string& file) : bundle(bundleSchema(file)) {
    try {
      valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
      const valijson::adapters::NlohmannJsonAdapter adapter(bundle);
      parser.populateSchema(adapter, schema);
    } catch (const std::exception& error) {
      throw Error(ErrorCode::Internal, fmt::format("schema does not compile: {}", error.what()),
                  file);
    }
  }
};

// Compiled on first use; entries are never removed, so references stay valid.
const CompiledSchema& compiledSchema(const std::string& file) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<CompiledSchema>> compiled;
  std::lock_guard lock(mutex);
  std::unique_ptr<CompiledSchema>& entry = compiled[file];
  if (!entry) entry = std::make_unique<CompiledSchema>(file);
  return *entry;
}

// What a valijson error is about. valijson 1.0 reports only a context path and an English
// description, so the kind is recognised from the description's fixed wording.
enum class IssueKind {
  Type,
  Enum,
  Const,
  Required,
  UnknownProperty,
  Minimum,
  ExclusiveMinimum,
  Maximum,
  ExclusiveMaximum,
  Pattern,
  ItemCount,
  Length,
  PropertyCount,
  Aggregate,  // "failed to validate X" wrappers around a more specific error
  Other,
};

struct Issue {
  IssueKind kind = IssueKind::Other;
  std::vector<std::string> tokens;  // of the value the error is about
  std::string property;             // Required / UnknownProperty: the member's name
  std::string description;          // valijson's text

  // Required and UnknownProperty are about a member one level below their context.
  std::size_t depth() const { return tokens.size() + (property.empty() ? 0 : 1); }
};

struct Pattern {
  std::string_view prefix;
  IssueKind kind;
};

// Longer prefixes first where one starts another ("less than or equal" before "less than").
constexpr Pattern kPatterns[] = {
    {"Value type not permitted", IssueKind::Type},
    {"Failed to match against any enum values", IssueKind::Enum},
    {"Failed to match expected value set by 'const'", IssueKind::Const},
    {"Missing required property", IssueKind::Required},
    {"Object contains a property that could not be validated", IssueKind::UnknownProperty},
    {"Expected number less than or equal to", IssueKind::Maximum},
    {"Expected number less than", IssueKind::ExclusiveMaximum},
    {"Expected number greater than or equal to", IssueKind::Minimum},
    {"Expected number greater than", IssueKind::ExclusiveMinimum},
    {"Failed to match regex specified by 'pattern'", IssueKind::Pattern},
    {"Array should contain", IssueKind::ItemCount},
    {"String should be no", IssueKind::Length},
    {"Object should have", IssueKind::PropertyCount},
    {"Failed to validate", IssueKind::Aggregate},
    {"Failed to any values", IssueKind::Aggregate},
};

IssueKind kindOf(std::string_view description) {
  for (const Pattern& pattern : kPatterns) {
    if (description.starts_with(pattern.prefix)) return pattern.kind;
  }
  return IssueKind::Other;
}

constexpr std::string_view kRequiredPrefix = "Missing required property '";
constexpr std::string_view kUnknownPrefix =
    "Object contains a property that could not be validated using 'properties' or "
    "'additionalProperties' constraints: '";

// The property name in "<prefix>name'.": everything between the fixed prefix and the closing
// quote, so names containing quotes survive.
std::string quotedName(std::string_view description, std::string_view prefix) {
  if (!description.starts_with(prefix)) return {};
  description.remove_prefix(prefix.size());
  if (description.ends_with("'.")) description.remove_suffix(2);
  return std::string(description);
}

// valijson's context is {"<root>", "[output]", "[width]"}: strip the brackets.
std::vector<std::string> tokensOf(const std::vector<std::string>& context) {
  std::vector<std::string> tokens;
  for (const std::string& entry : context) {
    if (entry.size() >= 2 && entry.front() == '[' && entry.back() == ']') {
      tokens.push_back(entry.substr(1, entry.size() - 2));
    }
  }
  return tokens;
}

Issue toIssue(const valijson::ValidationResults::Error& error) {
  Issue issue;
  issue.kind = kindOf(error.description);
  issue.tokens = tokensOf(error.context);
  issue.description = error.description;
  if (issue.kind == IssueKind::Required) {
    issue.property = quotedName(error.description, kRequiredPrefix);
  } else if (issue.kind == IssueKind::UnknownProperty) {
    issue.property = quotedName(error.description, kUnknownPrefix);
  }
  return issue;
}

bool isRangeIssue(IssueKind kind) {
  return kind == IssueKind::Minimum || kind == IssueKind::ExclusiveMinimum ||
         kind == IssueKind::Maximum || kind == IssueKind::ExclusiveMaximum;
}

// Whether `candidate` is a more specific complaint than `best`: deeper, or as deep and about the
// shape where `best` is about the range ("must be an integer" before "must be at least 1").
bool moreSpecific(const Issue& candidate, const Issue& best) {
  if (candidate.depth() != best.depth()) return candidate.depth() > best.depth();
  return isRangeIssue(best.kind) && !isRangeIssue(candidate.kind);
}

// The most specific non-aggregate error, the first one among equals.
Issue mostSpecific(const valijson::ValidationResults& results) {
  std::optional<Issue> best;
  for (const auto& error : results) {
    Issue issue = toIssue(error);
    if (issue.kind == IssueKind::Aggregate) continue;
    if (!best || moreSpecific(issue, *best)) best = std::move(issue);
  }
  if (best) return *best;
  return toIssue(*results.begin());
}

// --- Phrasing -------------------------------------------------------------------------------

std::string formatNumber(double value) { return fmt::format("{}", value); }

// A short rendering of a value for messages; never the whole of a large array or object.
std::string describeValue(const json* value) {
  if (value == nullptr) return "nothing";
  switch (value->type()) {
    case json::value_t::object:
      return "an object";
    case json::value_t::array:
      return fmt::format("an array of {} item{}", value->size(), value->size() == 1 ? "" : "s");
    case json::value_t::string: {
      constexpr std::size_t kMaxChars = 60;
      const std::string& text = value->get_ref<const std::string&>();
      const bool cut = text.size() > kMaxChars;
      return json(cut ? text.substr(0, kMaxChars) : text)
                 .dump(-1, ' ', false, json::error_handler_t::replace) +
             (cut ? "..." : "");
    }
    case json::value_t::number_float:
      return formatNumber(value->get<double>());
    default:
      return value->dump();
  }
}

std::string article(const std::string& type) {
  return (type == "integer" || type == "array" || type == "object") ? "an " + type : "a " + type;
}

// The values `key` has in the applicable schema nodes, first occurrence first.
std::vector<json> keywordValues(const Nodes& nodes, const char* key) {
  std::vector<json> values;
  for (const json* node : nodes) {
    const auto it = node->find(key);
    if (it != node->end() && std::find(values.begin(), values.end(), *it) == values.end()) {
      values.push_back(*it);
    }
  }
  return values;
}

std::optional<double> numericKeyword(const Nodes& nodes, const char* key) {
  for (const json& value : keywordValues(nodes, key)) {
    if (value.is_number()) return value.get<double>();
  }
  return std::nullopt;
}

// The bound at the end of "Expected number less than 8192.000000", for when the schema lookup
// found nothing.
std::string boundFromDescription(const std::string& description) {
  const std::size_t space = description.rfind(' ');
  return formatNumber(std::strtod(description.c_str() + space + 1, nullptr));
}

std::string boundText(const Issue& issue, const Nodes& nodes, const char* key) {
  const std::optional<double> bound = numericKeyword(nodes, key);
  return bound ? formatNumber(*bound) : boundFromDescription(issue.description);
}

std::string joinList(const std::vector<std::string>& items, std::string_view lastSeparator) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) text += (i + 1 == items.size()) ? lastSeparator : ", ";
    text += items[i];
  }
  return text;
}

std::string expectedTypes(const Nodes& nodes) {
  std::vector<std::string> types;
  for (const json& type : keywordValues(nodes, "type")) {
    for (const json& name : type.is_array() ? type : json::array({type})) {
      if (name.is_string()) types.push_back(article(name.get<std::string>()));
    }
  }
  return types.empty() ? "of another type" : joinList(types, " or ");
}

std::string allowedValues(const Nodes& nodes) {
  std::vector<std::string> values;
  for (const json& list : keywordValues(nodes, "enum")) {
    for (const json& value : list) values.push_back(value.dump());
  }
  return joinList(values, " or ");
}

std::vector<std::string> propertyNames(const Nodes& nodes) {
  std::vector<std::string> names;
  for (const json& properties : keywordValues(nodes, "properties")) {
    for (auto it = properties.begin(); it != properties.end(); ++it) {
      if (std::find(names.begin(), names.end(), it.key()) == names.end()) {
        names.push_back(it.key());
      }
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string itemCountMessage(const Nodes& nodes, const json* value) {
  const std::optional<double> min = numericKeyword(nodes, "minItems");
  const std::optional<double> max = numericKeyword(nodes, "maxItems");
  const std::size_t count = value != nullptr ? value->size() : 0;
  if (min && max && *min == *max) {
    return fmt::format("must have exactly {} items, got {}", formatNumber(*min), count);
  }
  if (min && count < *min) {
    return fmt::format("must have at least {} items, got {}", formatNumber(*min), count);
  }
  return fmt::format("must have at most {} items, got {}", formatNumber(max.value_or(0)), count);
}

std::string lengthMessage(const Issue& issue, const Nodes& nodes) {
  const std::optional<double> min = numericKeyword(nodes, "minLength");
  if (min && *min == 1) return "must not be empty";
  return issue.description;
}

std::string propertyCountMessage(const Nodes& nodes, const json* value) {
  const std::optional<double> min = numericKeyword(nodes, "minProperties");
  const std::optional<double> max = numericKeyword(nodes, "maxProperties");
  const std::size_t count = value != nullptr ? value->size() : 0;
  const std::string names = joinList(propertyNames(nodes), " or ");
  if (min && max && *min == 1 && *max == 1) {
    return fmt::format("must have exactly one property ({}), got {}", names, count);
  }
  return fmt::format("must have between {} and {} properties, got {}",
                     formatNumber(min.value_or(0)), max ? formatNumber(*max) : "any", count);
}

std::string messageFor(const Issue& issue, const Nodes& nodes, const json* value) {
  const std::string got = describeValue(value);
  switch (issue.kind) {
    case IssueKind::Type:
      return fmt::format("must be {}, got {}", expectedTypes(nodes), got);
    case IssueKind::Enum:
      return fmt::format("must be {}, got {}", allowedValues(nodes), got);
    case IssueKind::Const: {
      const std::vector<json> constants = keywordValues(nodes, "const");
      if (constants.empty()) return issue.description;
      return fmt::format("must be {}, got {}", constants.front().dump(), got);
    }
    case IssueKind::Required:
      return "is required";
    case IssueKind::UnknownProperty:
      return fmt::format("unknown property; allowed here: {}",
                         joinList(propertyNames(nodes), ", "));
    case IssueKind::Minimum:
      return fmt::format("must be at least {}, got {}", boundText(issue, nodes, "minimum"), got);
    case IssueKind::ExclusiveMinimum:
      return fmt::format("must be greater than {}, got {}",
                         boundText(issue, nodes, "exclusiveMinimum"), got);
    case IssueKind::Maximum:
      return fmt::format("must be at most {}, got {}", boundText(issue, nodes, "maximum"), got);
    case IssueKind::ExclusiveMaximum:
      return fmt::format("must be less than {}, got {}",
                         boundText(issue, nodes, "exclusiveMaximum"), got);
    case IssueKind::Pattern: {
      const std::vector<json> patterns = keywordValues(nodes, "pattern");
      if (patterns.empty()) return issue.description;
      return fmt::format("must match {}, got {}", patterns.front().get<std::string>(), got);
    }
    case IssueKind::ItemCount:
      return itemCountMessage(nodes, value);
    case IssueKind::Length:
      return lengthMessage(issue, nodes);
    case IssueKind::PropertyCount:
      return propertyCountMessage(nodes, value);
    case IssueKind::Aggregate:
    case IssueKind::Other:
      break;
  }
  return issue.description;
}

// Range violations are 422 (the request is well-formed, the value is not acceptable); everything
// else is a malformed request, 400.
ErrorCode codeFor(IssueKind kind) {
  return isRangeIssue(kind) ? ErrorCode::Invalid : ErrorCode::BadRequest;
}

Error toError(const Issue& issue, const json& bundle, const json& request) {
  // Required/UnknownProperty: the message is about the parent's schema (which properties it
  // has), the field is the member.
  const Nodes nodes = schemaNodesAt(bundle, request, issue.tokens);
  const json* value = valueAt(request, issue.tokens);
  std::vector<std::string> fieldTokens = issue.tokens;
  if (!issue.property.empty()) fieldTokens.push_back(issue.property);
  const std::string field = fieldTokens.empty() ? "/" : joinPointer(fieldTokens);
  return Error(codeFor(issue.kind), messageFor(issue, nodes, value), field);
}

}  // namespace

void validateRequestSchema(const json& request) {
  validateAgainstProtoSchema(request, "render-request.schema.json");
}

void validateAgainstProtoSchema(const json& request, const std::string& schemaFile) {
  const CompiledSchema& compiled = compiledSchema(schemaFile);
  valijson::Validator validator(valijson::Validator::kStrongTypes);
  valijson::ValidationResults results;
  const valijson::adapters::NlohmannJsonAdapter target(request);
  if (validator.validate(compiled.schema, target, &results)) return;
  if (results.numErrors() == 0) {
    throw Error(ErrorCode::BadRequest, fmt::format("does not match {}", schemaFile), "/");
  }
  throw toError(mostSpecific(results), compiled.bundle, request);
}

}  // namespace lgh
