#include "lgh/bench/handoff_benchmark.hpp"

#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstring>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "core/stopwatch.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"
#include "scene/scene.hpp"
#include "shadows/ray_batch_transport.hpp"
#include "shadows/shadow_device.hpp"

namespace lgh::bench {
namespace {

constexpr std::size_t kMessageBytes = 64;

[[noreturn]] void failSystem(const std::string& what) {
  throw Error(ErrorCode::Internal, fmt::format("{} failed: {}", what, std::strerror(errno)));
}

void writeAll(int fd, const void* data, std::size_t size) {
  if (write(fd, data, size) != static_cast<ssize_t>(size)) failSystem("write");
}

void readAll(int fd, void* data, std::size_t size) {
  if (read(fd, data, size) != static_cast<ssize_t>(size)) failSystem("read");
}

// The child: answers every message with one of the same size; a message that carries file
// descriptors is answered after they are closed, as a sidecar would after importing them.
[[noreturn]] void echoChild(int socket) {
  std::array<char, kMessageBytes> message{};
  for (;;) {
    std::array<char, CMSG_SPACE(sizeof(int) * 3)> control{};
    iovec io{message.data(), message.size()};
    msghdr header{};
    header.msg_iov = &io;
    header.msg_iovlen = 1;
    header.msg_control = control.data();
    header.msg_controllen = control.size();
    const ssize_t got = recvmsg(socket, &header, 0);
    if (got <= 0) _exit(0);
    for (cmsghdr* c = CMSG_FIRSTHDR(&header); c != nullptr; c = CMSG_NXTHDR(&header, c)) {
      if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_RIGHTS) continue;
      const std::size_t count = (c->cmsg_len - CMSG_LEN(0)) / sizeof(int);
      for (std::size_t i = 0; i < count; ++i) {
        int fd = -1;
        std::memcpy(&fd, CMSG_DATA(c) + i * sizeof(int), sizeof(int));
        close(fd);
      }
    }
    if (write(socket, message.data(), static_cast<std::size_t>(got)) != got) _exit(1);
  }
}

void sendFds(int socket, const std::array<int, 3>& fds) {
  std::array<char, kMessageBytes> message{};
  std::array<char, CMSG_SPACE(sizeof(int) * 3)> control{};
  iovec io{message.data(), message.size()};
  msghdr header{};
  header.msg_iov = &io;
  header.msg_iovlen = 1;
  header.msg_control = control.data();
  header.msg_controllen = control.size();
  cmsghdr* c = CMSG_FIRSTHDR(&header);
  c->cmsg_level = SOL_SOCKET;
  c->cmsg_type = SCM_RIGHTS;
  c->cmsg_len = CMSG_LEN(sizeof(int) * fds.size());
  std::memcpy(CMSG_DATA(c), fds.data(), sizeof(int) * fds.size());
  if (sendmsg(socket, &header, 0) != static_cast<ssize_t>(message.size())) failSystem("sendmsg");
  readAll(socket, message.data(), message.size());
}

void measureSockets(const HandoffBenchmarkOptions& o, HandoffBenchmarkResult& result) {
  int pair[2] = {-1, -1};
  if (socketpair(AF_UNIX, SOCK_SEQPACKET, 0, pair) != 0) failSystem("socketpair");
  const pid_t child = fork();
  if (child < 0) failSystem("fork");
  if (child == 0) {
    close(pair[0]);
    echoChild(pair[1]);
  }
  close(pair[1]);
  TimingSamples samples;
  std::array<char, kMessageBytes> message{};
  for (int i = 0; i < o.warmupIterations + o.iterations; ++i) {
    const Stopwatch roundTrip;
    writeAll(pair[0], message.data(), message.size());
    readAll(pair[0], message.data(), message.size());
    if (i >= o.warmupIterations) samples.add("socket round trip", roundTrip.elapsedMs());
  }
  for (int i = 0; i < o.warmupIterations + o.iterations; ++i) {
    std::array<int, 3> fds{dup(0), dup(1), dup(2)};
    const Stopwatch passing;
    sendFds(pair[0], fds);
    if (i >= o.warmupIterations) samples.add("fd passing", passing.elapsedMs());
    for (int fd : fds) close(fd);
  }
  close(pair[0]);
  waitpid(child, nullptr, 0);
  result.socketRoundTrip = samples.stats("socket round trip");
  result.fdPassing = samples.stats("fd passing");
}

void measureInProcess(const HandoffBenchmarkOptions& o, HandoffBenchmarkResult& result) {
  const auto context = GlContext::create(o.renderer);
  result.device = context->info();
  ShadowDevice device;
  vk::ShadowTracer* tracer = device.tracer();
  result.shadows = device.info("");
  if (tracer == nullptr) {
    throw Error(ErrorCode::Unavailable, "this machine cannot trace: " + device.unavailableReason());
  }
  const auto scene = tracer->buildScene(Scene{});
  RayBatchTransport transport(*tracer, 0);
  const vk::RayBatchShape shape{1, 1, 1};
  const RayBatchTransport::GlBuffers buffers = transport.prepare(shape);
  const float origin[4] = {0.0F, 0.0F, 0.0F, 1.0F};
  const float target[4] = {0.0F, 1.0F, 0.0F, 1.0F};
  const vk::TracePath path =
      tracer->supports(vk::TracePath::RayQuery) ? vk::TracePath::RayQuery : vk::TracePath::Pipeline;
  TimingSamples samples;
  std::uint32_t bits = 0;
  for (int i = 0; i < o.warmupIterations + o.iterations; ++i) {
    const Stopwatch batch;
    glNamedBufferSubData(buffers.origins, 0, sizeof origin, origin);
    glNamedBufferSubData(buffers.targets, 0, sizeof target, target);
    transport.trace(*scene, path, shape, {});
    glGetNamedBufferSubData(buffers.visibility, 0, sizeof bits, &bits);
    if (i >= o.warmupIterations) samples.add("batch", batch.elapsedMs());
    tracer->collectTimings();
  }
  if (bits != 1U)
    throw Error(ErrorCode::Internal, "the hand-off benchmark's ray came back occluded");
  result.transport = transport.name();
  result.inProcessBatch = samples.stats("batch");
}

}  // namespace

HandoffBenchmarkResult runHandoffBenchmark(const HandoffBenchmarkOptions& options) {
  if (options.iterations <= 0 || options.warmupIterations < 0) {
    throw Error(ErrorCode::BadRequest, "iterations must be > 0 (warm-up >= 0)");
  }
  HandoffBenchmarkResult result;
  result.options = options;
  measureSockets(options, result);  // first: the child is forked before any GL or Vulkan
  measureInProcess(options, result);
  return result;
}

}  // namespace lgh::bench
