#include "daemon_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace lghd::test {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

AssetRoot makeAssetRoot() {
  char pattern[] = "/tmp/lghd-http-test-XXXXXX";
  if (mkdtemp(pattern) == nullptr) throw std::runtime_error("mkdtemp failed");
  AssetRoot assets{fs::path(pattern) / "assets", fs::path(pattern)};
  fs::copy(assimpDir(), assets.root, fs::copy_options::recursive);
  const fs::path glb = assimpDir() / "BoxTextured-glTF-Binary/BoxTextured.glb";
  fs::copy_file(glb, assets.outside / "secret.glb");
  fs::create_symlink(assets.outside / "secret.glb", assets.root / "escape.glb");
  fs::create_directory_symlink(assimpDir(), assets.root / "escape_dir");
  return assets;
}

struct AssetRootCleanup {
  ~AssetRootCleanup() {
    if (!path.empty()) {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  }
  fs::path path;
};
AssetRootCleanup cleanup;

// A daemon that closes a connection while the client still writes (411, 413) must not kill the
// test process with SIGPIPE: httplib's client writes with plain send().
const bool sigpipeIgnored = [] {
  std::signal(SIGPIPE, SIG_IGN);
  return true;
}();

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> result;
  result.reserve(strings.size() + 1);
  for (std::string& text : strings) result.push_back(text.data());
  result.push_back(nullptr);
  return result;
}

std::vector<std::string> environmentWith(const std::vector<std::string>& extra) {
  std::vector<std::string> env;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    if (std::strncmp(*entry, "LGHD_", 5) != 0) env.emplace_back(*entry);  // no leaks from outside
  }
  // The suite's context path (scripts/run-tests runs it on each) is lghd's LGHD_BACKEND.
  if (const char* backend = std::getenv("LGH_BACKEND"); backend != nullptr && *backend != 0) {
    env.push_back(std::string("LGHD_BACKEND=") + backend);
  }
  env.insert(env.end(), extra.begin(), extra.end());
  return env;
}

// Forks and execs lghd with stdout on a pipe and stderr to `stderrPath` (or inherited).
pid_t spawn(std::vector<std::string> argv, std::vector<std::string> env, int& stdoutFd,
            const fs::path& stderrPath) {
  int pipeFds[2];
  if (pipe2(pipeFds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  std::vector<char*> argvPointers = pointers(argv);
  std::vector<char*> envPointers = pointers(env);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);  // a crashed test must not leave its daemon behind
    dup2(pipeFds[1], STDOUT_FILENO);
    if (!stderrPath.empty()) {
      const int logFd = open(stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (logFd >= 0) dup2(logFd, STDERR_FILENO);
    }
    execve(argvPointers[0], argvPointers.data(), envPointers.data());
    _exit(127);
  }
  close(pipeFds[1]);
  stdoutFd = pipeFds[0];
  return pid;
}

std::string readLine(int fd, std::chrono::seconds timeout) {
  std::string line;
  const auto end = Clock::now() + timeout;
  while (Clock::now() < end) {
    pollfd entry{fd, POLLIN, 0};
    if (poll(&entry, 1, 100) <= 0) continue;
    char c = 0;
    if (read(fd, &c, 1) != 1) break;
    if (c == '\n') return line;
    line += c;
  }
  return line;
}

}  // namespace

fs::path assimpDir() { return "/usr/share/assimp/models/glTF2"; }

const AssetRoot& assetRoot() {
  static const AssetRoot assets = [] {
    AssetRoot made = makeAssetRoot();
    cleanup.path = made.outside;
    return made;
  }();
  return assets;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

DaemonProcess::DaemonProcess(std::vector<std::string> args, const std::vector<std::string>& env) {
  logPath_ = assetRoot().outside /
             ("lghd-" + std::to_string(Clock::now().time_since_epoch().count()) + ".log");
  std::vector<std::string> argv = {
      LGHD_BINARY, "--port", "0", "--asset-root", assetRoot().root.string(), "--log-level", "info"};
  argv.insert(argv.end(), args.begin(), args.end());
  pid_ = spawn(argv, environmentWith(env), stdoutFd_, logPath_);
  const std::string line = readLine(stdoutFd_, std::chrono::seconds(60));
  const std::string prefix = "listening on 127.0.0.1:";
  if (!line.starts_with(prefix)) {
    stop(SIGKILL, std::chrono::seconds(5));
    throw std::runtime_error("lghd did not report its port (got '" + line + "'):\n" + log());
  }
  port_ = std::stoi(line.substr(prefix.size()));
  if (std::find(args.begin(), args.end(), "--metrics-port") != args.end()) {
    const std::string metrics = readLine(stdoutFd_, std::chrono::seconds(60));
    const std::string metricsPrefix = "metrics on 127.0.0.1:";
    if (!metrics.starts_with(metricsPrefix)) {
      stop(SIGKILL, std::chrono::seconds(5));
      throw std::runtime_error("lghd did not report its metrics port (got '" + metrics + "')");
    }
    metricsPort_ = std::stoi(metrics.substr(metricsPrefix.size()));
  }
  waitUntilReady();
}

DaemonProcess::~DaemonProcess() {
  if (!exited() && !stop(SIGTERM, std::chrono::seconds(30))) stop(SIGKILL, std::chrono::seconds(5));
  if (stdoutFd_ >= 0) close(stdoutFd_);
}

void DaemonProcess::waitUntilReady() {
  const auto end = Clock::now() + std::chrono::seconds(120);
  auto http = client(std::chrono::seconds(5));
  while (Clock::now() < end) {
    if (exited()) throw std::runtime_error("lghd exited while starting:\n" + log());
    const auto response = http->Get("/readyz");
    if (response && response->status == 200) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  throw std::runtime_error("lghd did not become ready within 120 s:\n" + log());
}

std::unique_ptr<httplib::Client> DaemonProcess::client(std::chrono::seconds readTimeout) const {
  auto http = std::make_unique<httplib::Client>("127.0.0.1", port_);
  http->set_read_timeout(readTimeout);
  http->set_write_timeout(std::chrono::seconds(30));
  http->set_connection_timeout(std::chrono::seconds(5));
  return http;
}

bool DaemonProcess::exited() {
  if (exitStatus_) return true;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) != pid_) return false;
  exitStatus_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return true;
}

std::optional<int> DaemonProcess::stop(int signal, std::chrono::milliseconds timeout) {
  if (!exited()) kill(pid_, signal);
  const auto end = Clock::now() + timeout;
  while (!exited() && Clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!exited()) return std::nullopt;
  if (*exitStatus_ >= 128) return std::nullopt;
  return exitStatus_;
}

std::string DaemonProcess::log() const {
  try {
    return readFile(logPath_);
  } catch (const std::exception&) {
    return {};
  }
}

std::pair<int, std::string> runLghd(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {LGHD_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  int stdoutFd = -1;
  const pid_t pid = spawn(argv, environmentWith({}), stdoutFd, "");
  std::string output;
  char buffer[4096];
  ssize_t got = 0;
  while ((got = read(stdoutFd, buffer, sizeof buffer)) > 0) {
    output.append(buffer, static_cast<std::size_t>(got));
  }
  close(stdoutFd);
  int status = 0;
  waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace lghd::test
