#include "metrics_listener.hpp"

#include "lgh/thread_name.hpp"
#include "routes.hpp"

namespace lghd {

MetricsListener::MetricsListener(DaemonContext& context) {
  server_.new_task_queue = [] { return new httplib::ThreadPool(2); };
  addScrapeRoutes(server_, context);
}

MetricsListener::~MetricsListener() {
  server_.stop();
  if (thread_.joinable()) thread_.join();
}

int MetricsListener::start(const std::string& host, int port) {
  const int bound =
      port == 0 ? server_.bind_to_any_port(host) : (server_.bind_to_port(host, port) ? port : -1);
  if (bound < 0) return -1;
  thread_ = std::thread([this] {
    lgh::nameThisThread("lgh-metrics");
    server_.listen_after_bind();
  });
  return bound;
}

}  // namespace lghd
