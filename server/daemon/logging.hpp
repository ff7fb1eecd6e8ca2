// Structured logging: one JSON object per line on stderr ({"ts", "level", "event", ...}), or
// plain text with --log-format text. Messages of the renderer library go through the same logger
// (as {"msg": ...} in JSON mode). Request ids tie a request's log lines to its response.
#pragma once

#include <string>
#include <string_view>

#include <spdlog/common.h>
#include <nlohmann/json.hpp>

namespace lghd::logging {

// format: "json" or "text"; level: trace..off.
void setUp(const std::string& level, const std::string& format);

// Logs the event `name` with `fields` merged into the line.
void event(spdlog::level::level_enum level, std::string_view name,
           const nlohmann::json& fields = nlohmann::json::object());

// A fresh request id: 16 hex digits.
std::string newRequestId();
// The client's X-Request-Id when it is a sane token (1..128 of [A-Za-z0-9._:-]), else a fresh one.
std::string requestIdFrom(const std::string& header);

}  // namespace lghd::logging
