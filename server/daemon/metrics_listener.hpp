// The optional second listener (--metrics-port): GET /metrics, /healthz and /readyz, the same
// answers as on the main port, but without the bearer token, because Prometheus' Kubernetes
// scrape annotations cannot carry one. Nothing else is served there. It runs on a thread of its
// own, with two HTTP workers, until it is destroyed.
#pragma once

#include <string>
#include <thread>

#include "daemon_context.hpp"
#include "framed_server.hpp"

namespace lghd {

class MetricsListener {
 public:
  explicit MetricsListener(DaemonContext& context);
  ~MetricsListener();
  MetricsListener(const MetricsListener&) = delete;
  MetricsListener& operator=(const MetricsListener&) = delete;

  // Binds host:port (0: any free port) and starts serving. Returns the port, or -1.
  int start(const std::string& host, int port);

 private:
  FramedServer server_;
  std::thread thread_;
};

}  // namespace lghd
