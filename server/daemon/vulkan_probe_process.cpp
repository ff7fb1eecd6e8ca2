#include "vulkan_probe_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

extern char** environ;

namespace lghd {
namespace {

// The pipe's two ends, closed when they go out of scope.
class Pipe {
 public:
  Pipe() {
    if (pipe2(fds_.data(), O_CLOEXEC) != 0) fds_ = {-1, -1};
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  ~Pipe() {
    closeRead();
    closeWrite();
  }
  bool ok() const { return fds_[0] >= 0; }
  int readEnd() const { return fds_[0]; }
  int writeEnd() const { return fds_[1]; }
  void closeRead() { closeEnd(0); }
  void closeWrite() { closeEnd(1); }

 private:
  void closeEnd(int end) {
    if (fds_[end] >= 0) close(fds_[end]);
    fds_[end] = -1;
  }
  std::array<int, 2> fds_{-1, -1};
};

std::string readAll(int fd) {
  std::string text;
  std::array<char, 4096> buffer{};
  for (;;) {
    const ssize_t count = read(fd, buffer.data(), buffer.size());
    if (count > 0) {
      text.append(buffer.data(), static_cast<std::size_t>(count));
    } else if (count == 0 || errno != EINTR) {
      return text;
    }
  }
}

lgh::VulkanInfo failure(std::string message) {
  lgh::VulkanInfo info;
  info.error = std::move(message);
  return info;
}

lgh::VulkanInfo fromJson(const nlohmann::json& json) {
  lgh::VulkanInfo info;
  info.available = json.at("available").get<bool>();
  if (json.at("loader_version").is_string()) info.loaderVersion = json["loader_version"];
  info.error = json.value("error", "");
  for (const auto& device : json.at("devices")) {
    lgh::VulkanDeviceInfo entry;
    entry.name = device.at("name");
    entry.type = device.at("type");
    entry.apiVersion = device.at("api_version");
    entry.driverVersion = device.at("driver_version");
    entry.vendorId = device.at("vendor_id");
    entry.deviceId = device.at("device_id");
    entry.accelerationStructure = device.at("acceleration_structure");
    entry.rayQuery = device.at("ray_query");
    entry.rayTracingPipeline = device.at("ray_tracing_pipeline");
    info.devices.push_back(std::move(entry));
  }
  return info;
}

std::string exitText(int status) {
  if (WIFEXITED(status)) return fmt::format("exit status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("signal {}", WTERMSIG(status));
  return "unknown status";
}

}  // namespace

int printVulkanProbe() {
  spdlog::set_level(spdlog::level::off);  // stdout carries the report alone; the parent logs it
  std::cout << lgh::probeVulkan().toJson().dump() << std::endl;
  return 0;
}

lgh::VulkanInfo probeVulkanInChildProcess(std::atomic<pid_t>& child) {
  Pipe output;
  if (!output.ok()) return failure(fmt::format("pipe: {}", std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, output.writeEnd(), STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::string self = "/proc/self/exe";
  std::string flag = kProbeVulkanFlag;
  std::array<char*, 3> argv{self.data(), flag.data(), nullptr};
  // lghd blocks SIGTERM/SIGINT in every thread for its shutdown supervisor; the child must not
  // inherit that mask.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, self.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) {
    return failure(fmt::format("cannot start the probe: {}", std::strerror(spawned)));
  }
  child = pid;
  output.closeWrite();
  const std::string text = readAll(output.readEnd());
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  child = 0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return failure("the Vulkan probe process failed (" + exitText(status) + ")");
  }
  try {
    return fromJson(nlohmann::json::parse(text));
  } catch (const std::exception& error) {
    return failure(std::string("the Vulkan probe printed no valid report: ") + error.what());
  }
}

}  // namespace lghd
