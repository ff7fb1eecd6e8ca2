// The HTTP routes, one registration function per file.
#pragma once

#include <httplib.h>

#include "daemon_context.hpp"

namespace lghd {

// POST /v1/render
void addRenderRoutes(httplib::Server& server, DaemonContext& context);
// POST /v1/thumbnails
void addThumbnailRoutes(httplib::Server& server, DaemonContext& context);
// POST /v1/jobs, GET and DELETE /v1/jobs/{id}, GET /v1/jobs/{id}/result
void addJobRoutes(httplib::Server& server, DaemonContext& context);
// GET /healthz, /readyz, /v1/info, /metrics
void addStatusRoutes(httplib::Server& server, DaemonContext& context);
// GET /healthz, /readyz, /metrics only (the --metrics-port listener)
void addScrapeRoutes(httplib::Server& server, DaemonContext& context);
// GET /openapi.json and the JSON Schemas it references
void addDocumentRoutes(httplib::Server& server);
// POST /v1/benchmark, GET /v1/benchmark, GET /v1/benchmark/result (routes_benchmark.cpp)
void addBenchmarkRoutes(httplib::Server& server, DaemonContext& context);

}  // namespace lghd
