// The contract's texts checked against the code: proto/openapi.json's routes and methods against
// the daemon's route table; every "METHOD /path" that a proto text, docs/DAEMON.md or README.md
// names against it too; every default a proto text states ("--max-vpls, 1048576 by default")
// against lghd's own; the error codes and the metric families the document lists against the
// daemon's; the thumbnails and job schemas' defaults against their parsers. tests/contract lints
// the same document with a real OpenAPI linter and generates a client from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config.hpp"
#include "http_conventions.hpp"
#include "job_work.hpp"
#include "jobs.hpp"
#include "lgh/request.hpp"
#include "metrics.hpp"
#include "process_metrics.hpp"
#include "render_queue.hpp"
#include "thumbnails.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;

const std::vector<std::string> kProtoFiles = {"openapi.json",
                                              "camera.schema.json",
                                              "light.schema.json",
                                              "render-request.schema.json",
                                              "render-response.schema.json",
                                              "render-settings.schema.json",
                                              "scene.schema.json",
                                              "timings.schema.json",
                                              "thumbnails-request.schema.json",
                                              "job-request.schema.json",
                                              "job-status.schema.json",
                                              "benchmark-result.schema.json"};

json openapi() { return json::parse(lgh::protoDocument("openapi.json")); }

std::string readSource(const std::string& relativePath) {
  std::ifstream in(std::string(LGH_SOURCE_DIR) + "/" + relativePath);
  EXPECT_TRUE(in) << relativePath;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every string of a JSON document ("description", "summary", ...), with its JSON Pointer.
void collectTexts(const json& node, const std::string& path,
                  std::vector<std::pair<std::string, std::string>>& out) {
  if (node.is_string()) {
    out.emplace_back(path, node.get<std::string>());
  } else if (node.is_structured()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string key = node.is_object() ? it.key() : std::to_string(out.size());
      collectTexts(it.value(), std::string(path).append("/").append(key), out);
    }
  }
}

std::vector<std::pair<std::string, std::string>> protoTexts() {
  std::vector<std::pair<std::string, std::string>> texts;
  for (const std::string& file : kProtoFiles) {
    collectTexts(json::parse(lgh::protoDocument(file)), file + "#", texts);
  }
  return texts;
}

// lghd's defaults as parsed from an empty command line (what --help prints).
DaemonConfig defaultConfig() {
  char name[] = "lghd";
  char* argv[] = {name, nullptr};
  ParsedConfig parsed = parseConfig(1, argv);
  EXPECT_TRUE(parsed.config.has_value());
  return parsed.config.value_or(DaemonConfig{});
}

// --- Routes --------------------------------------------------------------------------------------

TEST(Contract, OpenApiPathsAndMethodsAreTheDaemonsRoutes) {
  const json document = openapi();
  std::map<std::string, std::set<std::string>> documented;
  for (const auto& [path, item] : document.at("paths").items()) {
    for (const auto& [key, operation] : item.items()) {
      if (key == "parameters") continue;
      std::string method = key;
      std::transform(method.begin(), method.end(), method.begin(), ::toupper);
      documented[path].insert(method);
    }
  }
  std::map<std::string, std::set<std::string>> served;
  for (const RouteSpec& route : routeTable()) {
    for (std::string_view method : route.methods) {
      served[std::string(route.path)].insert(std::string(method));
    }
  }
  EXPECT_EQ(documented, served);
}

TEST(Contract, EveryRouteNamedInATextExists) {
  const std::regex mention(R"(\b(GET|POST|PUT|DELETE|PATCH) (/[A-Za-z0-9_./{}-]*[A-Za-z0-9_}]))");
  std::vector<std::pair<std::string, std::string>> texts = protoTexts();
  for (const char* doc : {"docs/DAEMON.md", "README.md", "docs/DEPLOYMENT.md"}) {
    texts.emplace_back(doc, readSource(doc));
  }
  int mentions = 0;
  for (const auto& [where, text] : texts) {
    for (auto it = std::sregex_iterator(text.begin(), text.end(), mention);
         it != std::sregex_iterator(); ++it) {
      const std::string method = (*it)[1];
      const std::string path = (*it)[2];
      ++mentions;
      const RouteSpec* route = matchRoute(path);
      ASSERT_NE(route, nullptr) << where << " names " << method << " " << path;
      EXPECT_NE(std::find(route->methods.begin(), route->methods.end(), method),
                route->methods.end())
          << where << " names " << method << " " << path;
    }
  }
  EXPECT_GT(mentions, 20);
}

TEST(Contract, NegotiationOffersOfFixedRoutesAreWhatTheDocumentSays) {
  const json document = openapi();
  for (const RouteSpec& route : routeTable()) {
    if (route.offers.empty()) continue;
    const json& item = document.at("paths").at(std::string(route.path));
    for (std::string_view method : route.methods) {
      std::string key(method);
      std::transform(key.begin(), key.end(), key.begin(), ::tolower);
      const json& responses = item.at(key).at("responses");
      const std::string ok = responses.contains("200") ? "200" : "202";
      for (const auto& [mime, media] : responses.at(ok).at("content").items()) {
        EXPECT_NE(std::find(route.offers.begin(), route.offers.end(), mime), route.offers.end())
            << route.path << " " << method << " documents " << mime;
      }
      EXPECT_TRUE(responses.contains("406")) << route.path << " " << method;
    }
  }
}

// --- Defaults and limits ---------------------------------------------------------------------

TEST(Contract, DefaultsTheTextsStateAreLghds) {
  const DaemonConfig config = defaultConfig();
  const std::map<std::string, long long> defaults = {
      {"--max-width", config.limits.maxWidth},
      {"--max-height", config.limits.maxHeight},
      {"--max-pixels", config.limits.maxPixels},
      {"--max-lights", config.limits.maxLights},
      {"--max-vpls", config.limits.maxVpls},
      {"--max-batch", config.limits.maxBatch},
      {"--max-body-mb", static_cast<long long>(config.limits.maxBodyBytes >> 20)},
      {"--deadline-seconds", config.deadline.count() / 1000},
      {"--max-job-batch", config.jobs.maxBatch},
      {"--max-jobs", config.jobs.maxJobs},
      {"--jobs-memory-mb", static_cast<long long>(config.jobs.memoryBytes >> 20)},
      {"--job-ttl-seconds", config.jobs.ttl.count()},
      {"--job-deadline-seconds", config.jobs.renderDeadline.count() / 1000},
  };
  const std::regex stated(R"((--[a-z-]+), (\d+)( MiB)? by default)");
  int checked = 0;
  for (const auto& [where, text] : protoTexts()) {
    for (auto it = std::sregex_iterator(text.begin(), text.end(), stated);
         it != std::sregex_iterator(); ++it) {
      const std::string flag = (*it)[1];
      ASSERT_TRUE(defaults.contains(flag)) << where << " states a default of " << flag;
      EXPECT_EQ(std::stoll((*it)[2]), defaults.at(flag)) << where << ": " << (*it)[0];
      ++checked;
    }
  }
  EXPECT_GE(checked, 10);
}

// docs/DAEMON.md's configuration table: "| `--flag` | `VARIABLE` | `default` | ...".
TEST(Contract, TheDaemonDocsConfigurationTableStatesLghdsDefaults) {
  const DaemonConfig config = defaultConfig();
  const std::map<std::string, long long> defaults = {
      {"--port", config.port},
      {"--http-threads", config.httpThreads},
      {"--grace-seconds", config.grace.count() / 1000},
      {"--queue-depth", config.queueDepth},
      {"--deadline-seconds", config.deadline.count() / 1000},
      {"--scene-cache-mb", static_cast<long long>(config.sceneCacheBytes >> 20)},
      {"--max-body-mb", static_cast<long long>(config.limits.maxBodyBytes >> 20)},
      {"--max-width", config.limits.maxWidth},
      {"--max-height", config.limits.maxHeight},
      {"--max-pixels", config.limits.maxPixels},
      {"--max-lights", config.limits.maxLights},
      {"--max-vpls", config.limits.maxVpls},
      {"--max-triangles", static_cast<long long>(config.limits.maxTriangles)},
      {"--max-texture-size", config.limits.maxTextureSize},
      {"--max-batch", config.limits.maxBatch},
      {"--max-jobs", config.jobs.maxJobs},
      {"--jobs-memory-mb", static_cast<long long>(config.jobs.memoryBytes >> 20)},
      {"--job-ttl-seconds", config.jobs.ttl.count()},
      {"--max-job-batch", config.jobs.maxBatch},
      {"--job-deadline-seconds", config.jobs.renderDeadline.count() / 1000},
  };
  const std::regex row(R"(^\| (`--[a-z-]+`(?:, `--[a-z-]+`)*) \| [^|]* \| `(\d+)` \|)");
  const std::regex flag(R"(--[a-z-]+)");
  std::set<std::string> checked;
  std::istringstream lines(readSource("docs/DAEMON.md"));
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (!std::regex_search(line, match, row)) continue;
    const std::string flags = match[1];
    for (auto it = std::sregex_iterator(flags.begin(), flags.end(), flag);
         it != std::sregex_iterator(); ++it) {
      const std::string name = (*it)[0];
      if (!defaults.contains(name)) continue;
      EXPECT_EQ(std::stoll(match[2]), defaults.at(name)) << line;
      checked.insert(name);
    }
  }
  for (const auto& [name, value] : defaults) {
    EXPECT_TRUE(checked.contains(name)) << "docs/DAEMON.md's table lacks " << name;
  }
}

TEST(Contract, WhatLghRenderAllowsIsTheRenderersDefaultLimits) {
  const lgh::RequestLimits limits;
  const json settings = json::parse(lgh::protoDocument("render-settings.schema.json"));
  const std::string vpls =
      settings.at("$defs").at("lgh").at("properties").at("vpl_count").at("description");
  EXPECT_NE(vpls.find("lgh-render allows " + std::to_string(limits.maxVpls)), std::string::npos)
      << vpls;
  const json scene = json::parse(lgh::protoDocument("scene.schema.json"));
  const std::string glb = scene.at("properties").at("glb_base64").at("description");
  EXPECT_NE(
      glb.find("lgh-render allows " + std::to_string(limits.maxInlineGlbBytes >> 20) + " MiB"),
      std::string::npos)
      << glb;
}

// The thumbnails schema's defaults, sent explicitly, give the batch that leaving them out gives.
TEST(Contract, ThumbnailsSchemaDefaultsAreTheParsers) {
  const json schema = json::parse(lgh::protoDocument("thumbnails-request.schema.json"));
  const lgh::RequestLimits limits;
  const json minimal = {{"assets", {"a.glb"}}};
  const ThumbnailBatch reference = parseThumbnailBatch(minimal, {}, limits, 64);
  int checked = 0;
  for (const auto& [name, property] : schema.at("properties").items()) {
    if (!property.contains("default")) continue;
    json request = minimal;
    request[name] = property["default"];
    const ThumbnailBatch batch = parseThumbnailBatch(request, {}, limits, 64);
    ASSERT_EQ(batch.items.size(), reference.items.size()) << name;
    EXPECT_EQ(batch.format, reference.format) << name;
    const ThumbnailItem& got = batch.items.front();
    const ThumbnailItem& want = reference.items.front();
    EXPECT_EQ(got.fileName, want.fileName) << name;
    EXPECT_EQ(got.view, want.view) << name;
    ASSERT_TRUE(got.request && want.request);
    EXPECT_EQ(got.request->output.width, want.request->output.width) << name;
    EXPECT_EQ(got.request->output.height, want.request->output.height) << name;
    EXPECT_EQ(got.request->output.pngCompression, want.request->output.pngCompression) << name;
    EXPECT_EQ(got.request->output.transparentBackground, want.request->output.transparentBackground)
        << name;
    EXPECT_EQ(got.request->camera.viewDirection, want.request->camera.viewDirection) << name;
    EXPECT_EQ(got.request->camera.margin, want.request->camera.margin) << name;
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

TEST(Contract, JobSchemaDefaultsAreTheParsers) {
  const json schema = json::parse(lgh::protoDocument("job-request.schema.json"));
  const json& benchmark = schema.at("$defs").at("benchmark").at("properties");
  const DaemonConfig config = defaultConfig();
  Metrics metrics;
  const auto implicit =
      parseJobWork({{"kind", "benchmark"}}, config, config.requestLimits(), metrics);
  const auto explicitDefaults =
      parseJobWork({{"kind", "benchmark"},
                    {"warmup", benchmark.at("warmup").at("default")},
                    {"iterations", benchmark.at("iterations").at("default")}},
                   config, config.requestLimits(), metrics);
  EXPECT_EQ(implicit->size(), explicitDefaults->size());
  EXPECT_EQ(implicit->size(), 11U);  // warmup 1 + iterations 10
}

// --- Errors and metrics ------------------------------------------------------------------------

TEST(Contract, ErrorCodesAreTheDaemons) {
  std::set<std::string> codes = {"unauthorized",
                                 "length_required",
                                 "queue_full",
                                 "method_not_allowed",
                                 "not_acceptable",
                                 "conflict",
                                 "http_version_not_supported"};
  for (lgh::ErrorCode code :
       {lgh::ErrorCode::BadRequest, lgh::ErrorCode::NotFound, lgh::ErrorCode::TooLarge,
        lgh::ErrorCode::Invalid, lgh::ErrorCode::Unavailable, lgh::ErrorCode::Timeout,
        lgh::ErrorCode::Internal}) {
    codes.insert(std::string(lgh::errorCodeName(code)));
  }
  const json document = openapi();
  const json& documented = document.at("components")
                               .at("schemas")
                               .at("ErrorDetail")
                               .at("properties")
                               .at("code")
                               .at("enum");
  EXPECT_EQ(documented.get<std::set<std::string>>(), codes);
  const std::string daemonDoc = readSource("docs/DAEMON.md");
  for (const std::string& code : codes) {
    EXPECT_NE(daemonDoc.find("| `" + code + "` |"), std::string::npos)
        << "docs/DAEMON.md's error table lacks " << code;
  }
}

std::set<std::string> familiesIn(const std::string& exposition) {
  std::set<std::string> families;
  std::istringstream lines(exposition);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("# TYPE ")) continue;
    families.insert(line.substr(7, line.find(' ', 7) - 7));
  }
  return families;
}

std::set<std::string> familiesNamedIn(const std::string& text) {
  const std::regex name(R"(\b((?:lghd|process)_[a-z_]+[a-z]))");
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), name); it != std::sregex_iterator();
       ++it) {
    names.insert((*it)[1]);
  }
  return names;
}

TEST(Contract, MetricFamiliesAreTheDocumentedOnes) {
  Metrics metrics;
  RenderQueue queue({}, metrics);
  JobStore jobs(JobLimits{}, queue);
  const std::set<std::string> exposed = familiesIn(metrics.exposition(RuntimeGauges{}) +
                                                   jobs.exposition() + processMetricsExposition());
  const json document = openapi();
  const std::string description = document.at("paths").at("/metrics").at("get").at("description");
  EXPECT_EQ(familiesNamedIn(description), exposed);

  // docs/DAEMON.md's metrics table names each family in backquotes.
  const std::string daemonDoc = readSource("docs/DAEMON.md");
  for (const std::string& family : exposed) {
    EXPECT_NE(daemonDoc.find("`" + family + "`"), std::string::npos)
        << "docs/DAEMON.md does not document " << family;
  }
}

}  // namespace
}  // namespace lghd
