// metrics.hpp: counters and histograms, and /metrics in the Prometheus text format (0.0.4):
// metric names, labels with escaped values, cumulative buckets, HELP and TYPE before each family.
// The exposition is read back with a small parser of that format, so the checks are on what a
// Prometheus server would see, not on string fragments.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "lgh/timing.hpp"
#include "metrics.hpp"
#include "version.hpp"

namespace lghd {
namespace {

using Labels = std::map<std::string, std::string>;

struct Sample {
  std::string name;
  Labels labels;
  double value = 0.0;
};

struct Family {
  std::string type;
  std::string help;
};

// The exposition, parsed. A line that breaks the format fails the test that parses it.
struct Exposition {
  std::map<std::string, Family> families;  // by name, from # HELP and # TYPE
  std::vector<Sample> samples;

  // The value of the series `name{labels}`, if there is one.
  std::optional<double> value(const std::string& name, const Labels& labels = {}) const {
    for (const Sample& sample : samples) {
      if (sample.name == name && sample.labels == labels) return sample.value;
    }
    return std::nullopt;
  }
};

const std::regex kMetricName("[a-zA-Z_:][a-zA-Z0-9_:]*");
const std::regex kLabelName("[a-zA-Z_][a-zA-Z0-9_]*");

// `name="value",...}` from `pos` (just after the '{'); returns the position after the '}'.
std::size_t parseLabels(const std::string& line, std::size_t pos, Labels& labels) {
  while (pos < line.size() && line[pos] != '}') {
    const std::size_t equals = line.find('=', pos);
    if (equals == std::string::npos) throw std::runtime_error("label without '='");
    const std::string name = line.substr(pos, equals - pos);
    if (!std::regex_match(name, kLabelName)) throw std::runtime_error("bad label name " + name);
    pos = equals + 1;
    if (pos >= line.size() || line[pos] != '"') throw std::runtime_error("unquoted label value");
    std::string value;
    for (++pos; pos < line.size() && line[pos] != '"'; ++pos) {
      if (line[pos] != '\\') {
        value += line[pos];
        continue;
      }
      if (++pos >= line.size()) throw std::runtime_error("escape at the end of the line");
      switch (line[pos]) {
        case '\\':
          value += '\\';
          break;
        case '"':
          value += '"';
          break;
        case 'n':
          value += '\n';
          break;
        default:
          throw std::runtime_error(std::string("unknown escape \\") + line[pos]);
      }
    }
    if (pos >= line.size()) throw std::runtime_error("unterminated label value");
    if (!labels.emplace(name, value).second) throw std::runtime_error("label twice: " + name);
    ++pos;  // the closing quote
    if (pos < line.size() && line[pos] == ',') ++pos;
  }
  if (pos >= line.size()) throw std::runtime_error("no closing brace");
  return pos + 1;
}

double parseValue(const std::string& text) {
  if (text == "+Inf") return INFINITY;
  if (text == "-Inf") return -INFINITY;
  if (text == "NaN") return NAN;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw std::runtime_error("bad value '" + text + "'");
  return value;
}

// The family a sample belongs to: histograms own their _bucket, _sum and _count series.
std::string familyOf(const std::string& name, const std::map<std::string, Family>& families) {
  for (const char* suffix : {"_bucket", "_sum", "_count"}) {
    const std::string text = suffix;
    if (name.ends_with(text)) {
      std::string base = name.substr(0, name.size() - text.size());
      const auto it = families.find(base);
      if (it != families.end() && it->second.type == "histogram") return base;
    }
  }
  return name;
}

Exposition parseExposition(const std::string& text) {
  if (text.empty() || text.back() != '\n') throw std::runtime_error("must end with a newline");
  Exposition exposition;
  std::set<std::string> seriesSeen;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    if (line.starts_with("# HELP ") || line.starts_with("# TYPE ")) {
      const std::size_t nameEnd = line.find(' ', 7);
      const std::string name = line.substr(7, nameEnd - 7);
      if (!std::regex_match(name, kMetricName)) throw std::runtime_error("bad name: " + line);
      const std::string rest = nameEnd == std::string::npos ? "" : line.substr(nameEnd + 1);
      Family& family = exposition.families[name];
      if (line[2] == 'H') {
        if (!family.type.empty()) throw std::runtime_error("HELP after TYPE: " + line);
        family.help = rest;
      } else {
        if (!std::set<std::string>{"counter", "gauge", "histogram"}.contains(rest)) {
          throw std::runtime_error("unknown type: " + line);
        }
        family.type = rest;
      }
      continue;
    }
    if (line.empty() || line[0] == '#') throw std::runtime_error("unexpected line: " + line);
    Sample sample;
    std::size_t pos = line.find_first_of("{ ");
    if (pos == std::string::npos) throw std::runtime_error("no value: " + line);
    sample.name = line.substr(0, pos);
    if (!std::regex_match(sample.name, kMetricName)) throw std::runtime_error("bad name: " + line);
    if (line[pos] == '{') pos = parseLabels(line, pos + 1, sample.labels);
    if (pos >= line.size() || line[pos] != ' ') throw std::runtime_error("no value: " + line);
    sample.value = parseValue(line.substr(pos + 1));
    const auto family = exposition.families.find(familyOf(sample.name, exposition.families));
    if (family == exposition.families.end() || family->second.type.empty() ||
        family->second.help.empty()) {
      throw std::runtime_error("sample before its HELP and TYPE: " + line);
    }
    if (!seriesSeen.insert(line.substr(0, line.rfind(' '))).second) {
      throw std::runtime_error("series twice: " + line);
    }
    exposition.samples.push_back(std::move(sample));
  }
  return exposition;
}

// Each histogram series (one label set): buckets cumulative in order of le, ending with +Inf,
// whose count equals _count.
void expectHistogramsConsistent(const Exposition& exposition) {
  for (const auto& [name, family] : exposition.families) {
    if (family.type != "histogram") continue;
    std::map<Labels, std::vector<std::pair<double, double>>> buckets;  // by labels without le
    for (const Sample& sample : exposition.samples) {
      if (sample.name != name + "_bucket") continue;
      Labels labels = sample.labels;
      ASSERT_TRUE(labels.contains("le")) << name;
      const double le = parseValue(labels["le"]);
      labels.erase("le");
      buckets[labels].emplace_back(le, sample.value);
    }
    for (const auto& [labels, series] : buckets) {
      ASSERT_FALSE(series.empty());
      for (std::size_t i = 1; i < series.size(); ++i) {
        EXPECT_LT(series[i - 1].first, series[i].first) << name << ": le out of order";
        EXPECT_LE(series[i - 1].second, series[i].second) << name << ": buckets not cumulative";
      }
      EXPECT_TRUE(std::isinf(series.back().first)) << name << ": no +Inf bucket";
      EXPECT_EQ(exposition.value(name + "_count", labels), series.back().second) << name;
      EXPECT_TRUE(exposition.value(name + "_sum", labels)) << name;
    }
  }
}

lgh::TimingTable timings(double totalMs) {
  lgh::TimingTable table;
  table.add("scene_load", lgh::TimingRow::Clock::Cpu, 4.0);
  table.add("shadow", lgh::TimingRow::Clock::Gpu, 2.0);
  table.add("total", lgh::TimingRow::Clock::Cpu, totalMs);
  return table;
}

TEST(EscapeLabel, EscapesBackslashQuoteAndNewline) {
  EXPECT_EQ(escapeLabel("plain/v1:render-1.0"), "plain/v1:render-1.0");
  EXPECT_EQ(escapeLabel("a\\b"), "a\\\\b");
  EXPECT_EQ(escapeLabel("say \"hi\""), "say \\\"hi\\\"");
  EXPECT_EQ(escapeLabel("two\nlines"), "two\\nlines");
  EXPECT_EQ(escapeLabel(""), "");
}

TEST(Histogram, WritesCumulativeBucketsSumAndCount) {
  Histogram histogram({0.25, 1, 4});
  for (const double value : {0.125, 0.25, 0.5, 8.0}) histogram.observe(value);
  std::string out;
  histogram.write(out, "x_seconds", "");
  EXPECT_EQ(out,
            "x_seconds_bucket{le=\"0.25\"} 2\n"  // a value on a bound counts in that bucket (le)
            "x_seconds_bucket{le=\"1\"} 3\n"
            "x_seconds_bucket{le=\"4\"} 3\n"
            "x_seconds_bucket{le=\"+Inf\"} 4\n"
            "x_seconds_sum 8.875\n"
            "x_seconds_count 4\n");
}

TEST(Histogram, LabelsGoBeforeLe) {
  Histogram histogram({1});
  histogram.observe(0.5);
  std::string out;
  histogram.write(out, "y", "route=\"/v1/render\"");
  EXPECT_EQ(out,
            "y_bucket{route=\"/v1/render\",le=\"1\"} 1\n"
            "y_bucket{route=\"/v1/render\",le=\"+Inf\"} 1\n"
            "y_sum{route=\"/v1/render\"} 0.5\n"
            "y_count{route=\"/v1/render\"} 1\n");
}

TEST(Histogram, EmptyHasZeroes) {
  const Histogram histogram({0.5, 2});
  std::string out;
  histogram.write(out, "z", "");
  EXPECT_EQ(out,
            "z_bucket{le=\"0.5\"} 0\nz_bucket{le=\"2\"} 0\nz_bucket{le=\"+Inf\"} 0\n"
            "z_sum 0\nz_count 0\n");
}

TEST(Metrics, FreshExpositionIsWellFormed) {
  const Metrics metrics;
  const Exposition exposition = parseExposition(metrics.exposition({}));
  for (const char* name :
       {"lghd_build_info", "lghd_ready", "lghd_queue_depth", "lghd_queue_capacity",
        "lghd_render_in_progress", "lghd_scene_cache_hits_total", "lghd_scene_cache_misses_total",
        "lghd_scene_cache_entries", "lghd_scene_cache_bytes", "lghd_scene_cache_budget_bytes",
        "lghd_http_requests_total", "lghd_http_request_duration_seconds", "lghd_renders_total",
        "lghd_render_duration_seconds", "lghd_render_pass_seconds", "lghd_queue_wait_seconds",
        "lghd_thumbnails_total"}) {
    EXPECT_TRUE(exposition.families.contains(name)) << name;
  }
  EXPECT_EQ(exposition.families.at("lghd_http_requests_total").type, "counter");
  EXPECT_EQ(exposition.families.at("lghd_queue_depth").type, "gauge");
  EXPECT_EQ(exposition.families.at("lghd_queue_wait_seconds").type, "histogram");
  EXPECT_EQ(exposition.value("lghd_build_info", {{"version", kVersion}, {"image_io", kImageIo}}),
            1.0);
  EXPECT_EQ(exposition.value("lghd_queue_wait_seconds_count"), 0.0);
  EXPECT_FALSE(exposition.value("lghd_http_requests_total")) << "no series before a request";
  expectHistogramsConsistent(exposition);
}

TEST(Metrics, GaugesComeFromTheRuntimeValues) {
  RuntimeGauges gauges;
  gauges.queueDepth = 3;
  gauges.queueCapacity = 16;
  gauges.rendering = true;
  gauges.ready = true;
  gauges.sceneCacheHits = 41;
  gauges.sceneCacheMisses = 2;
  gauges.sceneCacheEntries = 2;
  gauges.sceneCacheBytes = 123456789;
  gauges.sceneCacheBudgetBytes = 512ULL << 20;
  const Exposition exposition = parseExposition(Metrics().exposition(gauges));
  EXPECT_EQ(exposition.value("lghd_queue_depth"), 3.0);
  EXPECT_EQ(exposition.value("lghd_queue_capacity"), 16.0);
  EXPECT_EQ(exposition.value("lghd_render_in_progress"), 1.0);
  EXPECT_EQ(exposition.value("lghd_ready"), 1.0);
  EXPECT_EQ(exposition.value("lghd_scene_cache_hits_total"), 41.0);
  EXPECT_EQ(exposition.value("lghd_scene_cache_misses_total"), 2.0);
  EXPECT_EQ(exposition.value("lghd_scene_cache_entries"), 2.0);
  EXPECT_EQ(exposition.value("lghd_scene_cache_bytes"), 123456789.0);
  EXPECT_EQ(exposition.value("lghd_scene_cache_budget_bytes"), 536870912.0);
  const Exposition idle = parseExposition(Metrics().exposition({}));
  EXPECT_EQ(idle.value("lghd_ready"), 0.0);
  EXPECT_EQ(idle.value("lghd_render_in_progress"), 0.0);
}

TEST(Metrics, RequestsByRouteMethodAndStatus) {
  Metrics metrics;
  metrics.recordRequest("/v1/render", "POST", 200, 0.02);
  metrics.recordRequest("/v1/render", "POST", 200, 0.2);
  metrics.recordRequest("/v1/render", "POST", 429, 0.0005);
  metrics.recordRequest("/healthz", "GET", 200, 0.0001);
  const Exposition exposition = parseExposition(metrics.exposition({}));
  const std::string requests = "lghd_http_requests_total";
  EXPECT_EQ(
      exposition.value(requests, {{"route", "/v1/render"}, {"method", "POST"}, {"status", "200"}}),
      2.0);
  EXPECT_EQ(
      exposition.value(requests, {{"route", "/v1/render"}, {"method", "POST"}, {"status", "429"}}),
      1.0);
  EXPECT_EQ(
      exposition.value(requests, {{"route", "/healthz"}, {"method", "GET"}, {"status", "200"}}),
      1.0);
  const std::string duration = "lghd_http_request_duration_seconds";
  EXPECT_EQ(exposition.value(duration + "_count", {{"route", "/v1/render"}}), 3.0);
  EXPECT_DOUBLE_EQ(exposition.value(duration + "_sum", {{"route", "/v1/render"}}).value_or(NAN),
                   0.2205);
  EXPECT_EQ(exposition.value(duration + "_bucket", {{"route", "/v1/render"}, {"le", "0.001"}}),
            1.0);
  EXPECT_EQ(exposition.value(duration + "_bucket", {{"route", "/v1/render"}, {"le", "0.025"}}),
            2.0);
  EXPECT_EQ(exposition.value(duration + "_bucket", {{"route", "/v1/render"}, {"le", "0.25"}}), 3.0);
  EXPECT_EQ(exposition.value(duration + "_count", {{"route", "/healthz"}}), 1.0);
  expectHistogramsConsistent(exposition);
}

// Label values with a backslash, a quote or a newline are escaped, and read back unchanged.
TEST(Metrics, LabelValuesAreEscaped) {
  Metrics metrics;
  const std::string route = "we\"ird\\route\nline";
  metrics.recordRequest(route, "GET", 404, 0.001);
  lgh::TimingTable table;
  table.add("pass \"quoted\"", lgh::TimingRow::Clock::Gpu, 1.0);
  metrics.recordRenderTimes(table, 0.0, false);
  const std::string text = metrics.exposition({});
  EXPECT_NE(text.find(R"(route="we\"ird\\route\nline")"), std::string::npos) << text;
  const Exposition exposition = parseExposition(text);
  EXPECT_EQ(exposition.value("lghd_http_requests_total",
                             {{"route", route}, {"method", "GET"}, {"status", "404"}}),
            1.0);
  EXPECT_EQ(exposition.value("lghd_render_pass_seconds_count",
                             {{"pass", "pass \"quoted\""}, {"clock", "gpu"}}),
            1.0);
}

TEST(Metrics, RenderAndThumbnailOutcomes) {
  Metrics metrics;
  for (const char* outcome : {"ok", "ok", "ok", "error", "timeout", "skipped", "skipped"}) {
    metrics.recordRender(outcome);
  }
  metrics.recordThumbnail("ok");
  metrics.recordThumbnail("error");
  metrics.recordThumbnail("ok");
  const Exposition exposition = parseExposition(metrics.exposition({}));
  EXPECT_EQ(exposition.value("lghd_renders_total", {{"outcome", "ok"}}), 3.0);
  EXPECT_EQ(exposition.value("lghd_renders_total", {{"outcome", "error"}}), 1.0);
  EXPECT_EQ(exposition.value("lghd_renders_total", {{"outcome", "timeout"}}), 1.0);
  EXPECT_EQ(exposition.value("lghd_renders_total", {{"outcome", "skipped"}}), 2.0);
  EXPECT_EQ(exposition.value("lghd_thumbnails_total", {{"status", "ok"}}), 2.0);
  EXPECT_EQ(exposition.value("lghd_thumbnails_total", {{"status", "error"}}), 1.0);
}

// The "total" row is the render time by scene-cache result; the other rows are passes, by clock;
// the queue wait has a histogram of its own. Times go in as milliseconds and out as seconds.
TEST(Metrics, RenderTimesByPassClockAndCache) {
  Metrics metrics;
  metrics.recordRenderTimes(timings(125.0), 0.5, false);
  metrics.recordRenderTimes(timings(25.0), 0.25, true);
  metrics.recordRenderTimes(timings(50.0), 0.0, true);
  const Exposition exposition = parseExposition(metrics.exposition({}));
  const std::string render = "lghd_render_duration_seconds";
  EXPECT_EQ(exposition.value(render + "_count", {{"scene_cache", "miss"}}), 1.0);
  EXPECT_EQ(exposition.value(render + "_sum", {{"scene_cache", "miss"}}), 0.125);
  EXPECT_EQ(exposition.value(render + "_count", {{"scene_cache", "hit"}}), 2.0);
  EXPECT_DOUBLE_EQ(exposition.value(render + "_sum", {{"scene_cache", "hit"}}).value_or(NAN),
                   0.075);
  const std::string pass = "lghd_render_pass_seconds";
  EXPECT_EQ(exposition.value(pass + "_count", {{"pass", "shadow"}, {"clock", "gpu"}}), 3.0);
  EXPECT_DOUBLE_EQ(
      exposition.value(pass + "_sum", {{"pass", "shadow"}, {"clock", "gpu"}}).value_or(NAN), 0.006);
  EXPECT_EQ(exposition.value(pass + "_count", {{"pass", "scene_load"}, {"clock", "cpu"}}), 3.0);
  EXPECT_FALSE(exposition.value(pass + "_count", {{"pass", "total"}, {"clock", "cpu"}}))
      << "the total is not a pass";
  EXPECT_EQ(exposition.value("lghd_queue_wait_seconds_count"), 3.0);
  EXPECT_EQ(exposition.value("lghd_queue_wait_seconds_sum"), 0.75);
  EXPECT_EQ(exposition.value("lghd_queue_wait_seconds_bucket", {{"le", "0.001"}}), 1.0);
  EXPECT_EQ(exposition.value("lghd_queue_wait_seconds_bucket", {{"le", "0.25"}}), 2.0);
  expectHistogramsConsistent(exposition);
}

// HTTP threads record while /metrics is scraped: no update may be lost.
TEST(Metrics, ConcurrentRecordingLosesNothing) {
  Metrics metrics;
  constexpr int kThreads = 4;
  constexpr int kPerThread = 2000;
  std::vector<std::thread> threads;
  threads.reserve(kThreads);
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&metrics] {
      for (int i = 0; i < kPerThread; ++i) {
        metrics.recordRequest("/v1/render", "POST", 200, 0.001);
        metrics.recordRender("ok");
      }
    });
  }
  for (int i = 0; i < 20; ++i) parseExposition(metrics.exposition({}));
  for (std::thread& thread : threads) thread.join();
  const Exposition exposition = parseExposition(metrics.exposition({}));
  const double total = kThreads * kPerThread;
  EXPECT_EQ(exposition.value("lghd_http_requests_total",
                             {{"route", "/v1/render"}, {"method", "POST"}, {"status", "200"}}),
            total);
  EXPECT_EQ(exposition.value("lghd_http_request_duration_seconds_count", {{"route", "/v1/render"}}),
            total);
  EXPECT_EQ(exposition.value("lghd_renders_total", {{"outcome", "ok"}}), total);
}

}  // namespace
}  // namespace lghd
