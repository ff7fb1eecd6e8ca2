#include "capped_header.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace lghd {
namespace {

// ASCII-only compact JSON: safe in a header value.
std::string compact(const nlohmann::json& value) {
  return value.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
}

std::string moreText(std::size_t left) {
  return fmt::format("... {} more (the JSON body, Accept: application/json, has them all)", left);
}

// Room for the marker entry: the longest it can be, plus punctuation.
constexpr std::size_t kMarkerBytes = 100;

}  // namespace

std::string cappedJsonArray(const std::vector<std::string>& items, std::size_t maxBytes) {
  std::string whole = compact(items);
  if (whole.size() <= maxBytes) return whole;
  nlohmann::json kept = nlohmann::json::array();
  std::size_t used = 2;  // []
  for (const std::string& item : items) {
    const std::size_t bytes = compact(item).size() + 1;  // and its comma
    if (used + bytes + kMarkerBytes > maxBytes) break;
    kept.push_back(item);
    used += bytes;
  }
  const std::size_t left = items.size() - kept.size();
  kept.push_back(moreText(left));
  return compact(kept);
}

std::string cappedJsonObject(const std::map<std::string, std::string>& entries,
                             std::size_t maxBytes) {
  std::string whole = compact(entries);
  if (whole.size() <= maxBytes) return whole;
  nlohmann::json kept = nlohmann::json::object();
  std::size_t used = 2;  // {}
  for (const auto& [key, value] : entries) {
    const std::size_t bytes = compact(key).size() + compact(value).size() + 2;  // : and ,
    if (used + bytes + kMarkerBytes > maxBytes) continue;
    kept[key] = value;
    used += bytes;
  }
  kept["truncated"] = moreText(entries.size() - kept.size());
  return compact(kept);
}

}  // namespace lghd
