#include "connection_stream.hpp"

#include "http_framing.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <thread>

namespace lghd {
namespace {

constexpr std::size_t kReadChunk = 16384;
// How long, and how much, a lingering close reads from a client that keeps sending.
constexpr auto kLingerTime = std::chrono::milliseconds(500);
constexpr std::size_t kLingerBytes = std::size_t{1} << 20;

bool pollFor(int fd, short events, std::chrono::microseconds timeout) {
  pollfd entry{fd, events, 0};
  const auto milliseconds =
      static_cast<int>(std::chrono::ceil<std::chrono::milliseconds>(std::max(timeout, {})).count());
  for (;;) {
    const int ready = ::poll(&entry, 1, milliseconds);
    if (ready >= 0) return ready > 0;
    if (errno != EINTR) return false;
  }
}

void addressOf(const sockaddr_storage& address, std::string& ip, int& port) {
  std::array<char, INET6_ADDRSTRLEN> text{};
  if (address.ss_family == AF_INET) {
    const auto& v4 = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &v4.sin_addr, text.data(), text.size());
    port = ntohs(v4.sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto& v6 = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &v6.sin6_addr, text.data(), text.size());
    port = ntohs(v6.sin6_port);
  }
  ip = text.data();
}

}  // namespace

ConnectionStream::ConnectionStream(int fd, std::chrono::microseconds readTimeout,
                                   std::chrono::microseconds writeTimeout)
    : fd_(fd), readTimeout_(readTimeout), writeTimeout_(writeTimeout) {}

bool ConnectionStream::waitReadable(std::chrono::microseconds timeout) const {
  return pollFor(fd_, POLLIN, timeout);
}

bool ConnectionStream::is_readable() const { return buffered() > 0 || waitReadable(readTimeout_); }

bool ConnectionStream::is_writable() const { return pollFor(fd_, POLLOUT, writeTimeout_); }

ssize_t ConnectionStream::fill() {
  if (!waitReadable(readTimeout_)) return -1;
  if (position_ > 0 && position_ == buffer_.size()) {
    buffer_.clear();
    position_ = 0;
  }
  const std::size_t old = buffer_.size();
  buffer_.resize(old + kReadChunk);
  ssize_t count = -1;
  do {
    count = ::recv(fd_, buffer_.data() + old, kReadChunk, 0);
  } while (count < 0 && errno == EINTR);
  buffer_.resize(old + static_cast<std::size_t>(std::max<ssize_t>(count, 0)));
  return count;
}

ssize_t ConnectionStream::read(char* ptr, size_t size) {
  if (buffered() == 0) {
    // Large reads (bodies) go straight to the caller; the buffer is for heads.
    if (size >= kReadChunk) {
      if (!waitReadable(readTimeout_)) return -1;
      ssize_t count = -1;
      do {
        count = ::recv(fd_, ptr, size, 0);
      } while (count < 0 && errno == EINTR);
      if (count > 0) bytesRead_ += static_cast<std::uint64_t>(count);
      return count;
    }
    const ssize_t count = fill();
    if (count <= 0) return count;
  }
  const std::size_t count = std::min(size, buffered());
  std::memcpy(ptr, buffer_.data() + position_, count);
  position_ += count;
  bytesRead_ += count;
  return static_cast<ssize_t>(count);
}

ssize_t ConnectionStream::write(const char* ptr, size_t size) {
  if (!is_writable()) return -1;
  ssize_t count = -1;
  do {
    count = ::send(fd_, ptr, size, MSG_NOSIGNAL);
  } while (count < 0 && errno == EINTR);
  return count;
}

void ConnectionStream::get_remote_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof(address);
  if (::getpeername(fd_, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    addressOf(address, ip, port);
  }
}

void ConnectionStream::get_local_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof(address);
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    addressOf(address, ip, port);
  }
}

bool ConnectionStream::waitForRequest(std::chrono::milliseconds idle,
                                      const std::function<bool()>& stopping) {
  constexpr auto kSlice = std::chrono::milliseconds(20);
  const auto end = std::chrono::steady_clock::now() + idle;
  while (buffered() == 0) {
    if (stopping()) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        end - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    if (!pollFor(fd_, POLLIN, std::min(left, kSlice))) continue;
    if (fill() <= 0) return false;
  }
  return !stopping();
}

ConnectionStream::Head ConnectionStream::readHead(std::size_t maxBytes) {
  std::size_t searched = 0;  // bytes after position_ known to hold no complete head
  for (;;) {
    // Empty lines before the request line (RFC 9112 2.2).
    while (buffered() >= 2 && buffer_.compare(position_, 2, "\r\n") == 0) position_ += 2;
    while (buffered() >= 1 && buffer_[position_] == '\n') ++position_;
    const std::string_view pending(buffer_.data() + position_, buffered());
    const std::size_t from = searched >= 2 ? searched - 2 : 0;
    const std::size_t length = findHeadEnd(pending.substr(from));
    if (length != std::string_view::npos) {
      headEnd_ = bytesRead_ + from + length;
      return {HeadStatus::Complete, pending.substr(0, from + length)};
    }
    if (pending.size() > maxBytes) return {HeadStatus::TooLarge, {}};
    searched = pending.size();
    if (!waitReadable(readTimeout_)) return {HeadStatus::TimedOut, {}};
    if (fill() <= 0) return {HeadStatus::Closed, {}};
  }
}

std::uint64_t ConnectionStream::bodyBytesRead() const {
  return bytesRead_ > headEnd_ ? bytesRead_ - headEnd_ : 0;
}

void ConnectionStream::lingeringClose() {
  ::shutdown(fd_, SHUT_WR);
  const auto end = std::chrono::steady_clock::now() + kLingerTime;
  std::array<char, 16384> sink{};
  std::size_t dropped = 0;
  while (dropped < kLingerBytes) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
        end - std::chrono::steady_clock::now());
    if (left.count() <= 0 || !pollFor(fd_, POLLIN, left)) break;
    const ssize_t count = ::recv(fd_, sink.data(), sink.size(), 0);
    if (count <= 0) break;
    dropped += static_cast<std::size_t>(count);
  }
  close();
}

void ConnectionStream::close() {
  if (fd_ < 0) return;
  ::shutdown(fd_, SHUT_RDWR);
  ::close(fd_);
  fd_ = -1;
}

}  // namespace lghd
