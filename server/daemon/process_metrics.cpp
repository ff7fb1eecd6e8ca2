#include "process_metrics.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

namespace lghd {
namespace {

std::string readText(const char* path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The fields of /proc/self/stat after the command name, which may contain spaces and parentheses:
// everything after the last ')'. fields[0] is the state (field 3 of proc(5)).
std::vector<std::string> statFields(const std::string& stat) {
  const std::size_t close = stat.rfind(')');
  std::vector<std::string> fields;
  if (close == std::string::npos) return fields;
  std::istringstream rest(stat.substr(close + 1));
  for (std::string field; rest >> field;) fields.push_back(field);
  return fields;
}

// proc(5) numbers fields from 1; statFields() starts at field 3.
double field(const std::vector<std::string>& fields, int number) {
  const std::size_t index = static_cast<std::size_t>(number - 3);
  return index < fields.size() ? std::stod(fields[index]) : 0.0;
}

double bootTimeSeconds() {
  std::istringstream stat(readText("/proc/stat"));
  for (std::string line; std::getline(stat, line);) {
    if (line.starts_with("btime ")) return std::stod(line.substr(6));
  }
  return 0.0;
}

std::optional<double> softFdLimit() {
  std::istringstream limits(readText("/proc/self/limits"));
  for (std::string line; std::getline(limits, line);) {
    if (!line.starts_with("Max open files")) continue;
    std::istringstream values(line.substr(std::string("Max open files").size()));
    std::string soft;
    values >> soft;
    if (soft == "unlimited" || soft.empty()) return std::nullopt;
    return std::stod(soft);
  }
  return std::nullopt;
}

double openFds() {
  std::error_code error;
  double count = 0;
  for (auto it = std::filesystem::directory_iterator("/proc/self/fd", error);
       !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
    ++count;
  }
  return count > 0 ? count - 1 : 0;  // less the descriptor of the listing itself
}

void metric(std::string& out, const char* name, const char* type, const char* help, double value) {
  out += fmt::format("# HELP {} {}\n# TYPE {} {}\n{} {}\n", name, help, name, type, name, value);
}

}  // namespace

std::optional<ProcessStats> readProcessStats() {
  const std::vector<std::string> fields = statFields(readText("/proc/self/stat"));
  if (fields.size() < 22) return std::nullopt;
  const double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  const double pageBytes = static_cast<double>(sysconf(_SC_PAGESIZE));
  ProcessStats stats;
  stats.cpuSeconds = (field(fields, 14) + field(fields, 15)) / ticks;  // utime + stime
  stats.threads = field(fields, 20);
  stats.startTimeSeconds = bootTimeSeconds() + field(fields, 22) / ticks;
  stats.virtualBytes = field(fields, 23);
  stats.residentBytes = field(fields, 24) * pageBytes;
  stats.openFds = openFds();
  stats.maxFds = softFdLimit();
  return stats;
}

std::string processMetricsExposition() {
  const std::optional<ProcessStats> stats = readProcessStats();
  if (!stats) return {};
  std::string out;
  metric(out, "process_cpu_seconds_total", "counter",
         "Total user and system CPU time spent in seconds.", stats->cpuSeconds);
  metric(out, "process_resident_memory_bytes", "gauge", "Resident memory size in bytes.",
         stats->residentBytes);
  metric(out, "process_virtual_memory_bytes", "gauge", "Virtual memory size in bytes.",
         stats->virtualBytes);
  metric(out, "process_open_fds", "gauge", "Number of open file descriptors.", stats->openFds);
  if (stats->maxFds) {
    metric(out, "process_max_fds", "gauge", "Maximum number of open file descriptors.",
           *stats->maxFds);
  }
  metric(out, "process_start_time_seconds", "gauge",
         "Start time of the process since unix epoch in seconds.", stats->startTimeSeconds);
  metric(out, "process_threads", "gauge", "Number of OS threads in the process.", stats->threads);
  return out;
}

}  // namespace lghd
