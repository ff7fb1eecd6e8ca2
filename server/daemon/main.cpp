// lghd: the HTTP render daemon. Startup: parse the configuration, bind the port (printing
// "listening on HOST:PORT" as the first line on stdout), start the render thread, serve.
// Shutdown (SIGTERM/SIGINT): /readyz turns 503 and new renders get 503, the listening socket
// closes, queued renders may finish within --grace-seconds, what is left is answered 503, the
// HTTP workers finish their answers, the render thread releases the GL context, exit 0.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string_view>
#include <thread>

#include <spdlog/spdlog.h>

#include "allocator_tuning.hpp"
#include "benchmark_runner.hpp"
#include "config.hpp"
#include "crash_report.hpp"
#include "daemon_context.hpp"
#include "lgh/scene_worker.hpp"
#include "logging.hpp"
#include "metrics_listener.hpp"
#include "server.hpp"
#include "shutdown.hpp"
#include "version.hpp"
#include "vulkan_probe_process.hpp"

namespace lghd {
namespace {

// How long the render thread may take to finish a render in progress once the HTTP side is done.
constexpr auto kRenderThreadStopWait = std::chrono::seconds(10);

// httplib::Server::stop() only acts once listen has started; a signal may come before that.
void stopListening(httplib::Server& server, const std::atomic<bool>& listenReturned) {
  while (!listenReturned && !server.is_running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!listenReturned) server.stop();
}

void shutdownSequence(const DaemonConfig& config, RenderQueue& queue, JobStore& jobs,
                      BenchmarkRunner& benchmarks, httplib::Server& server,
                      const std::atomic<bool>& listenReturned) {
  logging::event(spdlog::level::info, "shutdown", {{"grace_ms", config.grace.count()}});
  queue.stopAccepting();
  stopListening(server, listenReturned);
  const bool drained = queue.drain(config.grace);
  jobs.stop();  // the runner's next render would be refused: unfinished jobs fail with 503
  logging::event(spdlog::level::info, "drained", {{"all_finished", drained}});
  benchmarks.stop();
}

nlohmann::json startupFields(const DaemonConfig& config, int port) {
  return {{"version", kVersion},
          {"host", config.host},
          {"port", port},
          {"backend", config.context.backend},
          {"gpu", config.context.gpu},
          {"gpus", config.gpuList()},
          {"queue_depth", config.queueDepth},
          {"encode_threads", config.output.encoderCount()},
          {"scene_parsers", config.sceneWorker ? config.sceneParserCount() : 0},
          {"frames_in_flight", config.output.frameLimit()},
          {"deadline_ms", config.deadline.count()},
          {"auth", !config.authToken.empty()}};
}

int serve(const DaemonConfig& config) {
  ShutdownSupervisor::blockSignals();
  Metrics metrics;
  RenderQueue queue({config.rendererOptions(), static_cast<std::size_t>(config.queueDepth),
                     config.testRenderDelay, config.watchdog, config.output, config.gpuList(),
                     config.testContextLossGpu, config.testContextLossAfter},
                    metrics);
  JobStore jobs(config.jobs, queue);
  HttpServer server;
  BenchmarkRunner benchmarks(config.rendererOptions());
  DaemonContext context{config, config.requestLimits(), queue, metrics, jobs, &benchmarks};
  configureServer(server, context);
  server.setRejectionListener([&metrics](const FramedServer::Rejection& rejection) {
    metrics.recordRequest("other", "", rejection.error.status, 0.0);
  });

  const int port = bindServer(server, config.host, config.port);
  if (port < 0) {
    logging::event(spdlog::level::critical, "bind_failed",
                   {{"host", config.host}, {"port", config.port}});
    return 1;
  }
  std::cout << "listening on " << config.host << ":" << port << std::endl;
  logging::event(spdlog::level::info, "listening", startupFields(config, port));
  std::optional<MetricsListener> metricsListener;
  if (config.metricsPort >= 0) {
    metricsListener.emplace(context);
    const int metricsPort = metricsListener->start(config.host, config.metricsPort);
    if (metricsPort < 0) {
      logging::event(spdlog::level::critical, "bind_failed",
                     {{"host", config.host}, {"port", config.metricsPort}, {"for", "metrics"}});
      return 1;
    }
    std::cout << "metrics on " << config.host << ":" << metricsPort << std::endl;
    logging::event(spdlog::level::info, "metrics_listening", {{"port", metricsPort}});
  }

  std::atomic<bool> listenReturned = false;
  ShutdownSupervisor supervisor;
  supervisor.start(
      [&] { shutdownSequence(config, queue, jobs, benchmarks, server, listenReturned); });
  queue.start([&supervisor](int exitCode, const std::string& reason) {
    supervisor.requestStop(exitCode, reason);
  });
  jobs.start();
  server.listen_after_bind();
  listenReturned = true;
  supervisor.requestStop(0, "the HTTP server stopped");  // no-op after a signal
  supervisor.join();

  jobs.stop();  // after a fatal context failure no shutdown sequence ran
  // A hung render thread will not end: do not wait for it.
  const bool hung = supervisor.exitCode() == kExitRenderHung;
  if (!queue.stop(hung ? std::chrono::seconds(0) : kRenderThreadStopWait)) {
    logging::event(spdlog::level::critical, "render_thread_stuck",
                   {{"note", "exiting without releasing the GL context"}});
    spdlog::default_logger()->flush();
    std::fflush(nullptr);
    std::_Exit(supervisor.exitCode());
  }
  logging::event(spdlog::level::info, "stopped", {{"exit_code", supervisor.exitCode()}});
  return supervisor.exitCode();
}

}  // namespace
}  // namespace lghd

int main(int argc, char** argv) {
  lgh::installCrashReport("lghd");
  if (argc == 2 && std::string_view(argv[1]) == lghd::kProbeVulkanFlag) {
    return lghd::printVulkanProbe();
  }
  if (argc == 4 && std::string_view(argv[1]) == lghd::kRunBenchmarkFlag) {
    return lghd::runBenchmarkChild(argv[2], argv[3]);
  }
  if (argc >= 2 && argc <= 3 && std::string_view(argv[1]) == lghd::kSceneWorkerFlag) {
    lgh::keepFreedMemoryForReuse();
    lghd::logging::setUp("warn", "json");
    return lgh::runSceneParserWorker(lgh::kSceneWorkerFd, argc == 3 ? argv[2] : "");
  }
  lghd::ParsedConfig parsed = lghd::parseConfig(argc, argv);
  if (!parsed.config) return parsed.exitCode;
  lghd::logging::setUp(parsed.config->context.logLevel, parsed.config->logFormat);
  try {
    return lghd::serve(*parsed.config);
  } catch (const std::exception& error) {
    lghd::logging::event(spdlog::level::critical, "fatal", {{"error", error.what()}});
    return 1;
  }
}
