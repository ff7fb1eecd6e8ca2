// One client connection as httplib reads and writes it (an httplib::Stream), with a read buffer
// that lives as long as the connection, so that lghd can look at a request's raw head before
// httplib parses it (http_framing.hpp) and can tell afterwards how much of the body httplib read.
// httplib's own socket stream lives for one request, cannot be inspected, and is not declared in
// Debian's split header.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include <httplib.h>

namespace lghd {

class ConnectionStream : public httplib::Stream {
 public:
  ConnectionStream(int fd, std::chrono::microseconds readTimeout,
                   std::chrono::microseconds writeTimeout);

  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override { return fd_; }

  // Waits up to `idle` for the first byte of the next request: false on timeout, end of stream,
  // error, or as soon as `stopping` returns true (checked every few milliseconds).
  bool waitForRequest(std::chrono::milliseconds idle, const std::function<bool()>& stopping);

  enum class HeadStatus { Complete, Closed, TooLarge, TimedOut };
  struct Head {
    HeadStatus status = HeadStatus::Closed;
    std::string_view text;  // Complete: the head up to and including its empty line
  };
  // Buffers the next request's head: up to the first empty line (ended by LF or CRLF, so that a
  // bare-LF head is found and refused rather than waited for), at most `maxBytes`. Empty lines
  // before the request line are dropped (RFC 9112 2.2). The head stays unread: httplib reads it
  // next through read(), and the view is valid until then.
  Head readHead(std::size_t maxBytes);

  // Bytes read() has handed out beyond the head of the last readHead(): the body, as far as it
  // was read.
  std::uint64_t bodyBytesRead() const;

  // Ends the connection without losing the answer to a reset: no more writes, then what the client
  // still sends is read and dropped for a moment, then the socket is closed.
  void lingeringClose();
  // Closes at once (the client has closed its side, or the server is stopping).
  void close();

 private:
  bool waitReadable(std::chrono::microseconds timeout) const;
  // Reads once from the socket into the buffer: bytes read, 0 at end of stream, -1 on error or
  // timeout.
  ssize_t fill();
  std::size_t buffered() const { return buffer_.size() - position_; }

  int fd_;
  std::chrono::microseconds readTimeout_;
  std::chrono::microseconds writeTimeout_;
  std::string buffer_;
  std::size_t position_ = 0;     // buffer_[position_..] is not read yet
  std::uint64_t bytesRead_ = 0;  // handed out by read() since the connection opened
  std::uint64_t headEnd_ = 0;    // bytesRead_ at the end of the last head
};

}  // namespace lghd
