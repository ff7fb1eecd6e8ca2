// httplib::Server with lghd's own connection loop: every request's head is read off the
// connection and checked for framing (http_framing.hpp) before httplib parses it, a head that
// breaks a rule is answered here (400, 414, 431 or 505, JSON body) and its connection closed, and
// a connection is also closed after any request whose body httplib did not read whole (refused
// before reading, or a method httplib reads no body for), so that leftover body bytes are never
// parsed as a request. httplib 0.11 lets a subclass replace the loop: process_and_close_socket is
// virtual, and process_request, which parses and answers one request, is protected.
#pragma once

#include <functional>
#include <string>

#include <httplib.h>

#include "connection_stream.hpp"
#include "http_framing.hpp"

namespace lghd {

class FramedServer : public httplib::Server {
 public:
  struct Rejection {
    FramingError error;
    std::string requestId;
    std::string remoteAddress;
  };
  using RejectionListener = std::function<void(const Rejection&)>;

  // Both before listening.
  void setFramingLimits(const FramingLimits& limits) { limits_ = limits; }
  void setRejectionListener(RejectionListener listener) { listener_ = std::move(listener); }

 private:
  enum class Next { KeepOpen, Close, CloseLingering };

  bool process_and_close_socket(socket_t sock) override;
  Next serveRequest(ConnectionStream& stream, bool last);
  void reject(ConnectionStream& stream, const FramingError& error);

  FramingLimits limits_;
  RejectionListener listener_;
};

}  // namespace lghd
