// The standard process_* metrics of Prometheus client libraries (CPU time, memory, file
// descriptors, start time), read from /proc/self at scrape time, so that dashboards and alerts
// written for any exporter work on lghd too.
#pragma once

#include <optional>
#include <string>

namespace lghd {

struct ProcessStats {
  double cpuSeconds = 0.0;     // user + system
  double residentBytes = 0.0;  // RSS
  double virtualBytes = 0.0;
  double openFds = 0.0;
  std::optional<double> maxFds;   // the soft RLIMIT_NOFILE; empty when unlimited
  double startTimeSeconds = 0.0;  // since the Unix epoch
  double threads = 0.0;
};

// Reads /proc/self/stat, /proc/self/fd, /proc/self/limits and /proc/stat (boot time). nullopt
// where /proc is not mounted.
std::optional<ProcessStats> readProcessStats();

// process_cpu_seconds_total, process_resident_memory_bytes, process_virtual_memory_bytes,
// process_open_fds, process_max_fds, process_start_time_seconds and process_threads, with HELP
// and TYPE lines; "" when the stats cannot be read.
std::string processMetricsExposition();

}  // namespace lghd
