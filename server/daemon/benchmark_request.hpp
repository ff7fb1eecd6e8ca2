// The body of POST /v1/benchmark: the flags of `lgh-bench gi` as one JSON object (docs/DAEMON.md,
// "Benchmarks"), every field optional with the CLI's default. Parsed by the daemon (to answer
// mistakes at once, 400/413/422 naming the field) and again by the child process that runs it.
#pragma once

#include <nlohmann/json.hpp>

#include "lgh/bench/gi_benchmark.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/request.hpp"

namespace lghd {

// Throws ApiError: 400 for an unknown field or a wrong type, 422 for a value out of range, 413
// for sizes or VPL counts over `limits` (the daemon's request limits).
lgh::bench::GiBenchmarkOptions parseBenchmarkRequest(const nlohmann::json& body,
                                                     const lgh::RequestLimits& limits);

// The renderer options the child process renders with, as JSON and back.
nlohmann::json rendererOptionsJson(const lgh::RendererOptions& options);
lgh::RendererOptions rendererOptionsFromJson(const nlohmann::json& json);

}  // namespace lghd
