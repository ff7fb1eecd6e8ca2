// The real lghd binary as a child process for the HTTP tests: started on a free loopback port
// (--port 0; the port is read from its first stdout line) with a temporary asset root, and
// stopped with SIGTERM at the end.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <httplib.h>

namespace lghd::test {

// A temporary asset root shared by the tests of one process: a copy of Debian's
// assimp-testmodels glTF2 folder, plus traps for the sandbox:
//   escape.glb     symlink to a .glb outside the root
//   escape_dir     symlink to a folder outside the root
//   ../secret.glb  a valid .glb beside (outside) the root
struct AssetRoot {
  std::filesystem::path root;
  std::filesystem::path outside;  // the folder holding root and secret.glb
};
const AssetRoot& assetRoot();
// /usr/share/assimp/models/glTF2
std::filesystem::path assimpDir();
std::string readFile(const std::filesystem::path& path);

class DaemonProcess {
 public:
  // Starts lghd with --port 0 --asset-root <assetRoot> plus `args`, and `env` (NAME=VALUE) added
  // to the environment; waits until /readyz answers 200 (or throws after 60 s).
  explicit DaemonProcess(std::vector<std::string> args = {},
                         const std::vector<std::string>& env = {});
  ~DaemonProcess();
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;

  int port() const { return port_; }
  // The --metrics-port listener's port (its second stdout line); -1 without one.
  int metricsPort() const { return metricsPort_; }
  pid_t pid() const { return pid_; }
  std::unique_ptr<httplib::Client> client(
      std::chrono::seconds readTimeout = std::chrono::seconds(60)) const;

  // Sends `signal` and waits up to `timeout` for the exit. Returns the exit status, or nullopt
  // when it did not exit in time or died from a signal.
  std::optional<int> stop(int signal, std::chrono::milliseconds timeout);
  // Exited (and reaped) already?
  bool exited();
  // What it wrote on stderr so far (its log).
  std::string log() const;

 private:
  void waitUntilReady();

  pid_t pid_ = -1;
  int port_ = 0;
  int metricsPort_ = -1;
  int stdoutFd_ = -1;
  std::filesystem::path logPath_;
  std::optional<int> exitStatus_;
};

// Runs `lghd args...` to completion (for --help); returns its exit status and stdout.
std::pair<int, std::string> runLghd(const std::vector<std::string>& args);

}  // namespace lghd::test
