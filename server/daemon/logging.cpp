#include "logging.hpp"

#include <cctype>
#include <ctime>
#include <random>

#include <fmt/format.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace lghd::logging {
namespace {

// Marks a message that is already a JSON object, to be spliced rather than quoted.
constexpr char kStructured = '\x1e';
bool jsonMode = true;

std::string isoTime(spdlog::log_clock::time_point time) {
  const auto sinceEpoch = time.time_since_epoch();
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(sinceEpoch);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(sinceEpoch - seconds);
  const std::time_t whole = seconds.count();
  std::tm utc{};
  gmtime_r(&whole, &utc);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:03}Z", utc.tm_year + 1900,
                     utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                     millis.count());
}

class JsonLineFormatter final : public spdlog::formatter {
 public:
  void format(const spdlog::details::log_msg& msg, spdlog::memory_buf_t& dest) override {
    const std::string_view payload(msg.payload.data(), msg.payload.size());
    const auto level = spdlog::level::to_string_view(msg.level);
    std::string line = fmt::format(R"({{"ts":"{}","level":"{}",)", isoTime(msg.time),
                                   std::string_view(level.data(), level.size()));
    if (payload.size() > 2 && payload.front() == kStructured) {
      line.append(payload.substr(2));  // the object without its marker and opening brace
    } else {
      line += R"("msg":)" + nlohmann::json(std::string(payload)).dump() + "}";
    }
    line += '\n';
    dest.append(line.data(), line.data() + line.size());
  }
  std::unique_ptr<spdlog::formatter> clone() const override {
    return std::make_unique<JsonLineFormatter>();
  }
};

}  // namespace

void setUp(const std::string& level, const std::string& format) {
  jsonMode = format == "json";
  auto logger = spdlog::stderr_logger_mt("lghd");
  if (jsonMode) {
    logger->set_formatter(std::make_unique<JsonLineFormatter>());
  } else {
    logger->set_pattern("%Y-%m-%dT%H:%M:%S.%e %l %v");
  }
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::from_str(level));
  spdlog::flush_on(spdlog::level::info);
}

void event(spdlog::level::level_enum level, std::string_view name, const nlohmann::json& fields) {
  if (!spdlog::should_log(level)) return;
  if (!jsonMode) {
    spdlog::log(level, "{} {}", name, fields.dump());
    return;
  }
  nlohmann::json line = {{"event", name}};
  line.update(fields);
  spdlog::log(level, "{}{}", kStructured,
              line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

std::string newRequestId() {
  thread_local std::mt19937_64 generator{std::random_device{}()};
  return fmt::format("{:016x}", generator());
}

std::string requestIdFrom(const std::string& header) {
  if (header.empty() || header.size() > 128) return newRequestId();
  for (char c : header) {
    const bool sane =
        std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == ':' || c == '-';
    if (!sane) return newRequestId();
  }
  return header;
}

}  // namespace lghd::logging
