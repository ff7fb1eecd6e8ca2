#include "scene/worker/scene_worker.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstring>
#include <deque>
#include <functional>
#include <future>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <span>
#include <thread>
#include <utility>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "lgh/scene_worker.hpp"
#include "lgh/thread_name.hpp"
#include "scene/gltf/gltf_loader.hpp"

extern char** environ;

namespace lgh::worker {
namespace {

using Clock = std::chrono::steady_clock;

// AddressSanitizer reserves terabytes of address space for its shadow memory, which no data
// limit can hold; sanitized builds run the worker without one.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// A message is a header on the socket, and its bytes in shared memory: written once and read
// once, where a socket would copy them twice more. Jobs, and answers too large for the arena,
// travel in a sealed memfd passed with the header (SCM_RIGHTS): the seals (no writes, no
// shrinking) keep a worker gone bad from changing or truncating the bytes while the renderer
// reads them, which would otherwise fault the renderer's process.
//
// Answers travel in the worker's answer arena instead when they fit: a memfd the renderer makes
// when the worker starts (sealed against shrinking and growing, so that a reader within its size
// cannot fault) and offers it once, which both map for the worker's life. A new memfd per answer
// cost each large scene its pages twice over: made and zeroed by the worker's kernel calls, then
// mapped into the renderer and torn down again (about 11 ms of the 31 ms of an 8.6 MB scene on the
// development VM). The arena's pages stay. The worker could still write to it while the renderer
// reads; the renderer reads every byte once, into memory of its own, and checks what it read
// there (scene_wire.hpp), so a worker gone bad can garble its own answer and nothing else.
constexpr unsigned kSeals = F_SEAL_SEAL | F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE;
constexpr unsigned kArenaSeals = F_SEAL_SEAL | F_SEAL_SHRINK | F_SEAL_GROW;

enum class MessageKind : std::uint32_t {
  Sealed = 1,   // the bytes in the memfd that comes with the header
  InArena = 2,  // the bytes at the start of the answer arena; no memfd
  Arena = 3,    // the renderer's offer of the answer arena (the memfd), `length` bytes
};

struct MessageHeader {
  std::uint64_t length = 0;
  MessageKind kind = MessageKind::Sealed;
  std::uint32_t reserved = 0;
};

class UniqueFd {
 public:
  explicit UniqueFd(int fd = -1) : fd_(fd) {}
  ~UniqueFd() {
    if (fd_ >= 0) ::close(fd_);
  }
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept {
    if (this != &other) {
      if (fd_ >= 0) ::close(fd_);
      fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
  }
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// The header, and the memfd when there is one (`fd` >= 0).
bool sendHeader(int socket, const MessageHeader& message, int fd) {
  MessageHeader header = message;
  iovec part{&header, sizeof(header)};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
  msghdr envelope{};
  envelope.msg_iov = &part;
  envelope.msg_iovlen = 1;
  if (fd >= 0) {
    envelope.msg_control = control;
    envelope.msg_controllen = sizeof(control);
    cmsghdr* rights = CMSG_FIRSTHDR(&envelope);
    rights->cmsg_level = SOL_SOCKET;
    rights->cmsg_type = SCM_RIGHTS;
    rights->cmsg_len = CMSG_LEN(sizeof(int));
    std::memcpy(CMSG_DATA(rights), &fd, sizeof(fd));
  }
  ssize_t sent = -1;
  do {
    sent = ::sendmsg(socket, &envelope, MSG_NOSIGNAL);
  } while (sent < 0 && errno == EINTR);
  return sent == static_cast<ssize_t>(sizeof(header));
}

bool sendSealed(int socket, const Encoded& message) {
  const UniqueFd memory(::memfd_create("lgh-scene-message", MFD_CLOEXEC | MFD_ALLOW_SEALING));
  const std::size_t size = std::max<std::size_t>(message.size, 1);
  if (memory.get() < 0 || ::ftruncate(memory.get(), static_cast<off_t>(size)) != 0) return false;
  // MAP_POPULATE: the pages in one go, rather than one fault each while writing.
  void* mapped =
      ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_POPULATE, memory.get(), 0);
  if (mapped == MAP_FAILED) return false;
  message.write(static_cast<std::uint8_t*>(mapped));
  ::munmap(mapped, size);
  if (::fcntl(memory.get(), F_ADD_SEALS, kSeals) != 0) return false;
  return sendHeader(socket, {message.size, MessageKind::Sealed}, memory.get());
}

}  // namespace

// A shared mapping of a memfd, unmapped on destruction.
class SharedMapping {
 public:
  SharedMapping(int fd, std::size_t size, int protection) {
    void* data = ::mmap(nullptr, std::max<std::size_t>(size, 1), protection, MAP_SHARED, fd, 0);
    if (data != MAP_FAILED) {
      data_ = static_cast<std::uint8_t*>(data);
      size_ = size;
    }
  }
  ~SharedMapping() {
    if (data_ != nullptr) ::munmap(data_, std::max<std::size_t>(size_, 1));
  }
  SharedMapping(const SharedMapping&) = delete;
  SharedMapping& operator=(const SharedMapping&) = delete;

  bool mapped() const { return data_ != nullptr; }
  std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

namespace {

// An answer in the arena when it fits there, else in a sealed memfd of its own.
bool sendAnswer(int socket, const Encoded& message, const SharedMapping* arena) {
  if (arena == nullptr || message.size > arena->size()) return sendSealed(socket, message);
  message.write(arena->data());
  return sendHeader(socket, {message.size, MessageKind::InArena}, -1);
}

// A received message: a sealed memfd mapped read-only for as long as it lives, or a span of the
// answer arena.
class Message {
 public:
  std::span<const std::uint8_t> bytes() const { return bytes_; }
  void map(int fd, std::size_t size) {
    owned_.emplace(fd, size, PROT_READ);
    if (owned_->mapped()) bytes_ = {owned_->data(), size};
  }
  void borrow(std::span<const std::uint8_t> bytes) { bytes_ = bytes; }
  bool mapped() const { return bytes_.data() != nullptr; }

 private:
  std::optional<SharedMapping> owned_;
  std::span<const std::uint8_t> bytes_;
};

enum class ReadResult { Done, Closed, TimedOut, Malformed, ArenaOffered };

struct Received {
  MessageHeader header;
  UniqueFd memory;  // the memfd that came with it, if one did
};

// Waits for the next header until `deadline` (none: as long as it takes).
ReadResult receiveHeader(int socket, const Clock::time_point* deadline, Received& received) {
  while (deadline != nullptr) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(*deadline - Clock::now());
    if (left.count() <= 0) return ReadResult::TimedOut;
    pollfd entry{socket, POLLIN, 0};
    const int ready = ::poll(&entry, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready > 0) break;
    if (ready < 0 && errno != EINTR) return ReadResult::Closed;
  }
  iovec part{&received.header, sizeof(received.header)};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
  msghdr envelope{};
  envelope.msg_iov = &part;
  envelope.msg_iovlen = 1;
  envelope.msg_control = control;
  envelope.msg_controllen = sizeof(control);
  ssize_t length = -1;
  do {
    length = ::recvmsg(socket, &envelope, MSG_CMSG_CLOEXEC);
  } while (length < 0 && errno == EINTR);
  if (length <= 0) return ReadResult::Closed;
  if (const cmsghdr* rights = CMSG_FIRSTHDR(&envelope); rights != nullptr) {
    if (rights->cmsg_type != SCM_RIGHTS || rights->cmsg_len != CMSG_LEN(sizeof(int))) {
      return ReadResult::Malformed;
    }
    int fd = -1;
    std::memcpy(&fd, CMSG_DATA(rights), sizeof(fd));
    received.memory = UniqueFd(fd);
  }
  if (length != static_cast<ssize_t>(sizeof(received.header)) ||
      (envelope.msg_flags & (MSG_TRUNC | MSG_CTRUNC)) != 0) {
    return ReadResult::Malformed;
  }
  return ReadResult::Done;
}

bool sealedWith(int fd, unsigned seals, std::uint64_t length) {
  struct stat status {};
  return ::fstat(fd, &status) == 0 &&
         static_cast<std::uint64_t>(status.st_size) >= std::max<std::uint64_t>(length, 1) &&
         (static_cast<unsigned>(::fcntl(fd, F_GET_SEALS)) & seals) == seals;
}

// Waits for the next message until `deadline` (none: as long as it takes) and maps it, when it is
// sealed and at most `maxBytes` long, or finds it in `arena`. An offer of an arena (the worker's
// side: `offer` not null) is handed over in `offer` instead.
ReadResult receiveMessage(int socket, const Clock::time_point* deadline, std::uint64_t maxBytes,
                          const SharedMapping* arena, Message& message, Received* offer = nullptr) {
  Received received;
  if (const ReadResult result = receiveHeader(socket, deadline, received);
      result != ReadResult::Done) {
    return result;
  }
  const MessageHeader& header = received.header;
  const int fd = received.memory.get();
  switch (header.kind) {
    case MessageKind::Sealed:
      if (fd < 0 || header.length > maxBytes || !sealedWith(fd, kSeals, header.length)) break;
      message.map(fd, static_cast<std::size_t>(header.length));
      return message.mapped() ? ReadResult::Done : ReadResult::Malformed;
    case MessageKind::InArena:
      if (fd >= 0 || arena == nullptr || header.length > arena->size()) break;
      message.borrow({arena->data(), static_cast<std::size_t>(header.length)});
      return ReadResult::Done;
    case MessageKind::Arena:
      if (offer == nullptr || fd < 0 || !sealedWith(fd, kArenaSeals, header.length)) break;
      *offer = std::move(received);
      return ReadResult::ArenaOffered;
  }
  return ReadResult::Malformed;
}

// The worker asks for SIGKILL when its parent dies (PR_SET_PDEATHSIG), and Linux counts as its
// parent the *thread* that started it: a worker started from a scene prefetch's thread would be
// killed when that thread ends. Every worker is therefore started from this one thread, which
// lives as long as the process (it is never destroyed, so no exit handler waits for it).
class SpawnThread {
 public:
  static SpawnThread& instance() {
    static SpawnThread* const thread = new SpawnThread();
    return *thread;
  }

  // Runs `spawn` on the thread and returns its result (posix_spawn's error number).
  int run(std::function<int()> spawn) {
    auto task = std::make_shared<std::packaged_task<int()>>(std::move(spawn));
    std::future<int> result = task->get_future();
    {
      const std::lock_guard lock(mutex_);
      tasks_.emplace_back([task] { (*task)(); });
    }
    posted_.notify_one();
    return result.get();
  }

 private:
  SpawnThread() {
    std::thread([this] { loop(); }).detach();
  }

  [[noreturn]] void loop() {
    nameThisThread("lgh-spawn");
    for (;;) {
      std::function<void()> task;
      {
        std::unique_lock lock(mutex_);
        posted_.wait(lock, [this] { return !tasks_.empty(); });
        task = std::move(tasks_.front());
        tasks_.pop_front();
      }
      task();
    }
  }

  std::mutex mutex_;
  std::condition_variable posted_;
  std::deque<std::function<void()>> tasks_;
};

// The worker says it is ready with one byte, once its libraries are loaded.
constexpr char kReady = 'R';
constexpr auto kStartupTimeout = std::chrono::seconds(60);

bool sendReady(int socket) {
  ssize_t sent = -1;
  do {
    sent = ::send(socket, &kReady, 1, MSG_NOSIGNAL);
  } while (sent < 0 && errno == EINTR);
  return sent == 1;
}

bool waitForReady(int socket, Clock::time_point deadline) {
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return false;
    pollfd entry{socket, POLLIN, 0};
    const int ready = ::poll(&entry, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) return false;
    if (ready <= 0) continue;
    char byte = 0;
    const ssize_t received = ::recv(socket, &byte, 1, 0);
    return received == 1 && byte == kReady;
  }
}

std::string describeStatus(int status) {
  if (WIFEXITED(status)) return fmt::format("exit status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return fmt::format("signal {} ({})", signal, strsignal(signal));
  }
  return "an unknown end";
}

void setLimit(pid_t pid, __rlimit_resource resource, rlim_t value) {
  const rlimit limit{value, value};
  if (::prlimit(pid, resource, &limit, nullptr) != 0) {
    spdlog::warn("scene worker: could not set resource limit {}: {}", static_cast<int>(resource),
                 std::strerror(errno));
  }
}

Scene loadInThisProcess(const LoadJob& job) {
  return loadSceneSource(job.source, job.assetRoot, job.limits, job.options);
}

}  // namespace

SceneWorker::SceneWorker(SceneWorkerOptions options) : options_(std::move(options)) {
  try {
    start();
  } catch (const Error& error) {
    // Not fatal here: the first load tries again and fails that load if it still cannot.
    spdlog::error("scene worker: {}", error.message());
  }
}

SceneWorker::~SceneWorker() { stop(false); }

void SceneWorker::start() {
  int sockets[2];
  if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sockets) != 0) {
    throw Error(
        ErrorCode::Unavailable,
        fmt::format("the scene parser worker cannot start: socketpair: {}", std::strerror(errno)));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sockets[1], kSceneWorkerFd);
  // The daemon's client sockets and files are no business of the worker's.
  posix_spawn_file_actions_addclosefrom_np(&actions, kSceneWorkerFd + 1);
  std::vector<std::string> argv = {options_.executable.string()};
  argv.insert(argv.end(), options_.arguments.begin(), options_.arguments.end());
  std::vector<char*> pointers;
  pointers.reserve(argv.size() + 1);
  for (std::string& argument : argv) pointers.push_back(argument.data());
  pointers.push_back(nullptr);
  pid_t pid = -1;
  const int failed = SpawnThread::instance().run([&] {
    return ::posix_spawn(&pid, argv.front().c_str(), &actions, nullptr, pointers.data(), environ);
  });
  posix_spawn_file_actions_destroy(&actions);
  ::close(sockets[1]);
  if (failed != 0) {
    ::close(sockets[0]);
    throw Error(ErrorCode::Unavailable,
                fmt::format("the scene parser worker cannot start: {}: {}",
                            options_.executable.string(), std::strerror(failed)));
  }
  pid_ = pid;
  socket_ = sockets[0];
  // Before it gets any work: no core files of crashes, and the memory limit.
  setLimit(pid_, RLIMIT_CORE, 0);
  if (!kAddressSanitizer) setLimit(pid_, RLIMIT_DATA, options_.memoryBytes);
  // Its start-up (loading its libraries) must not count against the first load's time limit.
  const auto started = Clock::now();
  if (!waitForReady(socket_, started + kStartupTimeout)) {
    const std::string end = stop(true);
    throw Error(ErrorCode::Unavailable,
                fmt::format("the scene parser worker did not start ({})", end));
  }
  spdlog::info("scene worker: pid {} ready in {:.0f} ms", pid_,
               std::chrono::duration<double, std::milli>(Clock::now() - started).count());
  offerAnswerArena();
}

void SceneWorker::offerAnswerArena() {
  const std::size_t bytes = options_.answerArenaBytes;
  if (bytes == 0) return;
  const UniqueFd memory(::memfd_create("lgh-scene-answers", MFD_CLOEXEC | MFD_ALLOW_SEALING));
  const bool made = memory.get() >= 0 &&
                    ::ftruncate(memory.get(), static_cast<off_t>(bytes)) == 0 &&
                    ::fcntl(memory.get(), F_ADD_SEALS, kArenaSeals) == 0;
  auto arena = made ? std::make_unique<SharedMapping>(memory.get(), bytes, PROT_READ) : nullptr;
  if (!arena || !arena->mapped()) {
    spdlog::warn("scene worker: no answer arena ({}); each answer comes in memory of its own",
                 std::strerror(errno));
    return;
  }
  if (!sendHeader(socket_, {bytes, MessageKind::Arena}, memory.get())) {
    spdlog::warn("scene worker: pid {} did not take its answer arena", pid_);
    return;  // the next load finds the worker gone, or answers in memory of its own
  }
  answers_ = std::move(arena);
}

std::string SceneWorker::stop(bool kill) {
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
  answers_.reset();
  if (pid_ < 0) return "not running";
  if (kill) ::kill(pid_, SIGKILL);
  int status = 0;
  // A worker told to end by the closed socket exits at once; give it a moment, then kill it.
  for (int attempt = 0; attempt < 200; ++attempt) {
    const pid_t reaped = ::waitpid(pid_, &status, WNOHANG);
    if (reaped == pid_ || (reaped < 0 && errno != EINTR)) break;
    if (attempt == 199) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  pid_ = -1;
  return describeStatus(status);
}

LoadOutcome SceneWorker::exchange(const LoadJob& job, const std::string& displayName) {
  if (pid_ < 0) start();
  if (!sendSealed(socket_, encodeJob(job))) {
    const std::string end = stop(true);
    throw Error(ErrorCode::Unavailable,
                fmt::format("the scene parser worker stopped before taking the asset ({})", end));
  }
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(options_.timeoutSeconds));
  Message answer;
  // The answer cannot be larger than what the worker may hold in memory.
  const ReadResult result = receiveMessage(
      socket_, &deadline, options_.memoryBytes + (std::uint64_t{1} << 20), answers_.get(), answer);
  if (result == ReadResult::TimedOut) {
    stop(true);
    spdlog::error("scene worker: {} took longer than {} s to parse; the worker was killed",
                  displayName, options_.timeoutSeconds);
    throw Error(ErrorCode::TooLarge,
                fmt::format("parsing the asset took longer than this server's limit of {} s",
                            options_.timeoutSeconds),
                displayName);
  }
  if (result != ReadResult::Done) {
    const std::string end = stop(true);
    spdlog::error("scene worker: {} parsing {} ({}); a new worker starts with the next load",
                  result == ReadResult::Closed ? "crashed" : "answered garbage", displayName, end);
    throw Error(ErrorCode::Invalid,
                fmt::format("the asset crashed the scene parser ({}); it is refused, and the "
                            "server goes on with a new parser",
                            end),
                displayName);
  }
  LoadOutcome outcome;
  try {
    outcome = decodeOutcome(answer.bytes());
  } catch (const Error&) {
    stop(true);
    throw;
  }
  // The loader's words for an allocation that failed; here, one its memory limit refused.
  if (auto* error = std::get_if<Error>(&outcome);
      error != nullptr && error->code() == ErrorCode::TooLarge &&
      error->message().find("more memory than") != std::string::npos) {
    outcome = Error(ErrorCode::TooLarge,
                    fmt::format("the asset needs more memory than this server's scene parser may "
                                "use ({} MiB)",
                                options_.memoryBytes >> 20U),
                    error->field());
  }
  return outcome;
}

Scene SceneWorker::load(const LoadJob& job) {
  const std::lock_guard lock(mutex_);
  const std::string name =
      job.source.displayName.empty() ? job.source.assetPath : job.source.displayName;
  LoadOutcome outcome = exchange(job, name);
  if (auto* error = std::get_if<Error>(&outcome)) throw *error;
  return std::move(std::get<Scene>(outcome));
}

}  // namespace lgh::worker

namespace lgh {

int runSceneParserWorker(int fd, const std::string& testCrashMarker) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the daemon (see SpawnThread)
  if (::getppid() == 1) return 1;      // it died before the request took effect
  if (!worker::sendReady(fd)) return 1;
  std::unique_ptr<worker::SharedMapping> answers;  // the renderer's answer arena, once offered
  for (;;) {
    worker::LoadOutcome outcome = Error(ErrorCode::Internal, "no load happened");
    {
      worker::Message request;
      worker::Received offer;
      const worker::ReadResult result = worker::receiveMessage(
          fd, nullptr, std::numeric_limits<std::uint64_t>::max(), nullptr, request, &offer);
      if (result == worker::ReadResult::Closed) return 0;  // the renderer is done with us
      if (result == worker::ReadResult::ArenaOffered) {
        answers = std::make_unique<worker::SharedMapping>(
            offer.memory.get(), static_cast<std::size_t>(offer.header.length),
            PROT_READ | PROT_WRITE);
        if (!answers->mapped()) answers.reset();
        continue;
      }
      if (result != worker::ReadResult::Done) return 1;
      try {
        const worker::LoadJob job = worker::decodeJob(request.bytes());
        if (!testCrashMarker.empty() &&
            job.source.displayName.find(testCrashMarker) != std::string::npos) {
          std::raise(SIGSEGV);
        }
        outcome = worker::loadInThisProcess(job);
      } catch (const Error& error) {
        outcome = error;
      } catch (const std::bad_alloc&) {
        outcome = Error(ErrorCode::TooLarge,
                        "the asset needs more memory than the scene parser's limit allows");
      } catch (const std::exception& error) {
        outcome =
            Error(ErrorCode::Internal, fmt::format("the scene parser failed: {}", error.what()));
      }
    }
    if (!worker::sendAnswer(fd, worker::encodeOutcome(outcome), answers.get())) return 1;
  }
}

}  // namespace lgh
