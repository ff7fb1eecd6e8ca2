#include "benchmark_request.hpp"

#include <set>
#include <string>

#include <fmt/format.h>

#include "api_error.hpp"
#include "lgh/enum_names.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;

const std::set<std::string> kFields = {
    "suite",      "vpls",    "width",         "height",         "scene",        "bounces",
    "alpha",      "path",    "table3_vpls",   "interleave",     "iterations",   "warmup",
    "overdraw",   "quality", "quality_width", "quality_height", "quality_vpls", "quality_alphas",
    "pt_samples", "seed",    "shadow_jitter"};

ApiError invalid(const std::string& field, const std::string& message) {
  return fromLghError(lgh::Error(lgh::ErrorCode::Invalid, message, "/" + field));
}

ApiError tooLarge(const std::string& field, const std::string& message) {
  return fromLghError(lgh::Error(lgh::ErrorCode::TooLarge, message, "/" + field));
}

int integer(const json& body, const std::string& field, int fallback, int minimum, int maximum) {
  const auto it = body.find(field);
  if (it == body.end()) return fallback;
  if (!it->is_number_integer()) throw badRequest("must be an integer", "/" + field);
  const auto value = it->get<std::int64_t>();
  if (value < minimum || value > maximum) {
    throw invalid(field, fmt::format("must be {} to {}, got {}", minimum, maximum, value));
  }
  return static_cast<int>(value);
}

float positive(const json& body, const std::string& field, float fallback, float maximum) {
  const auto it = body.find(field);
  if (it == body.end()) return fallback;
  if (!it->is_number()) throw badRequest("must be a number", "/" + field);
  const double value = it->get<double>();
  if (!(value > 0.0) || value > maximum) {
    throw invalid(field, fmt::format("must be > 0 and at most {}, got {}", maximum, value));
  }
  return static_cast<float>(value);
}

bool boolean(const json& body, const std::string& field, bool fallback) {
  const auto it = body.find(field);
  if (it == body.end()) return fallback;
  if (!it->is_boolean()) throw badRequest("must be true or false", "/" + field);
  return it->get<bool>();
}

template <typename Enum>
Enum enumeration(const json& value, const std::string& field) {
  if (!value.is_string()) throw badRequest("must be a string", "/" + field);
  const auto parsed = lgh::enumFromName<Enum>(value.get<std::string>());
  if (!parsed) {
    throw invalid(field, fmt::format("must be one of {}, got \"{}\"", lgh::enumNameList<Enum>(),
                                     value.get<std::string>()));
  }
  return *parsed;
}

json arrayOf(const json& body, const std::string& field) {
  const json& value = body.at(field);
  if (!value.is_array() || value.empty()) {
    throw badRequest("must be a non-empty array", "/" + field);
  }
  return value;
}

void checkSize(int width, int height, const lgh::RequestLimits& limits, const std::string& prefix) {
  if (width > limits.maxWidth) {
    throw tooLarge(prefix + "width", fmt::format("must be at most {} on this server, got {}",
                                                 limits.maxWidth, width));
  }
  if (height > limits.maxHeight) {
    throw tooLarge(prefix + "height", fmt::format("must be at most {} on this server, got {}",
                                                  limits.maxHeight, height));
  }
}

int vplCount(const json& value, const std::string& field, const lgh::RequestLimits& limits) {
  if (!value.is_number_integer()) throw badRequest("must be an integer", "/" + field);
  const auto count = value.get<std::int64_t>();
  if (count < 1) throw invalid(field, fmt::format("must be at least 1, got {}", count));
  if (count > limits.maxVpls) {
    throw tooLarge(field,
                   fmt::format("must be at most {} on this server, got {}", limits.maxVpls, count));
  }
  return static_cast<int>(count);
}

void readVpls(const json& body, const lgh::RequestLimits& limits,
              lgh::bench::GiBenchmarkOptions& options) {
  if (body.contains("vpls")) {
    options.vplCounts.clear();
    const json list = arrayOf(body, "vpls");
    for (std::size_t i = 0; i < list.size(); ++i) {
      options.vplCounts.push_back(vplCount(list[i], fmt::format("vpls/{}", i), limits));
    }
  } else {
    for (const int count : options.vplCounts) {
      if (count > limits.maxVpls) {
        throw tooLarge("vpls", fmt::format("the default VPL counts reach {}, over this server's "
                                           "limit of {}: give vpls",
                                           count, limits.maxVpls));
      }
    }
  }
  if (body.contains("table3_vpls")) {
    options.table3Vpls = vplCount(body.at("table3_vpls"), "table3_vpls", limits);
  }
  if (body.contains("quality_vpls")) {
    options.qualityVpls = vplCount(body.at("quality_vpls"), "quality_vpls", limits);
  }
}

}  // namespace

lgh::bench::GiBenchmarkOptions parseBenchmarkRequest(const nlohmann::json& body,
                                                     const lgh::RequestLimits& limits) {
  if (!body.is_object()) throw badRequest("the body must be a JSON object", "/");
  for (const auto& [key, value] : body.items()) {
    if (!kFields.contains(key)) {
      throw badRequest(fmt::format("unknown field \"{}\"", key), "/" + key);
    }
  }
  if (body.contains("suite") && body.at("suite") != "gi") {
    throw invalid("suite", "the only suite is \"gi\" (lgh-bench gi)");
  }
  lgh::bench::GiBenchmarkOptions options;
  options.width = integer(body, "width", options.width, 1, 1 << 16);
  options.height = integer(body, "height", options.height, 1, 1 << 16);
  checkSize(options.width, options.height, limits, "");
  if (body.contains("scene")) {
    options.scene.kind = lgh::SceneSource::Kind::Builtin;
    options.scene.builtin = enumeration<lgh::BuiltinScene>(body.at("scene"), "scene");
    options.sceneName = body.at("scene").get<std::string>();
  }
  options.bounces = integer(body, "bounces", options.bounces, 1, 3);
  if (body.contains("shadow_jitter")) {
    const json& jitter = body.at("shadow_jitter");
    if (!jitter.is_number()) throw badRequest("must be a number", "/shadow_jitter");
    const double value = jitter.get<double>();
    if (!(value >= 0.0 && value <= 1.0)) {
      throw invalid("shadow_jitter", fmt::format("must be 0 to 1, got {}", value));
    }
    options.shadowJitter = static_cast<float>(value);
  }
  options.alpha = positive(body, "alpha", options.alpha, 16.0F);
  if (body.contains("path")) {
    options.path = enumeration<lgh::LightingPath>(body.at("path"), "path");
    if (options.path == lgh::LightingPath::Auto) {
      throw invalid("path", "must be raster or compute");
    }
  }
  if (body.contains("interleave")) {
    options.interleaves.clear();
    const json list = arrayOf(body, "interleave");
    for (std::size_t i = 0; i < list.size(); ++i) {
      options.interleaves.push_back(
          enumeration<lgh::InterleaveMode>(list[i], fmt::format("interleave/{}", i)));
    }
  }
  readVpls(body, limits, options);
  options.timedIterations = integer(body, "iterations", options.timedIterations, 1, 1000);
  options.warmupIterations = integer(body, "warmup", options.warmupIterations, 0, 1000);
  options.overdraw = boolean(body, "overdraw", options.overdraw);
  options.quality = boolean(body, "quality", options.quality);
  options.qualityWidth = integer(body, "quality_width", options.qualityWidth, 1, 1 << 16);
  options.qualityHeight = integer(body, "quality_height", options.qualityHeight, 1, 1 << 16);
  checkSize(options.qualityWidth, options.qualityHeight, limits, "quality_");
  if (body.contains("quality_alphas")) {
    options.qualityAlphas.clear();
    const json list = arrayOf(body, "quality_alphas");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = fmt::format("quality_alphas/{}", i);
      options.qualityAlphas.push_back(positive(json{{field, list[i]}}, field, 1.0F, 16.0F));
    }
  }
  options.pathTracedSamples = integer(body, "pt_samples", options.pathTracedSamples, 1, 1 << 16);
  if (body.contains("seed")) {
    const json& seed = body.at("seed");
    if (!seed.is_number_unsigned() || seed.get<std::uint64_t>() > 0xFFFFFFFFULL) {
      throw invalid("seed", "must be an integer from 0 to 4294967295");
    }
    options.seed = seed.get<std::uint32_t>();
  }
  return options;
}

nlohmann::json rendererOptionsJson(const lgh::RendererOptions& options) {
  return {{"backend", lgh::contextBackendName(options.backend)},
          {"gpu", options.gpuIndex},
          {"require_gpu", options.requireGpu},
          {"asset_root", options.assetRoot.string()},
          {"max_triangles", options.maxTriangles},
          {"max_texture_size", options.maxTextureSize}};
}

lgh::RendererOptions rendererOptionsFromJson(const nlohmann::json& json) {
  lgh::RendererOptions options;
  options.backend = lgh::parseContextBackend(json.at("backend").get<std::string>());
  options.gpuIndex = json.at("gpu").get<int>();
  options.requireGpu = json.at("require_gpu").get<bool>();
  options.assetRoot = json.at("asset_root").get<std::string>();
  options.maxTriangles = json.at("max_triangles").get<std::size_t>();
  options.maxTextureSize = json.at("max_texture_size").get<int>();
  return options;
}

}  // namespace lghd
