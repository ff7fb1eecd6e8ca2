// The httplib::Server of the daemon: routes plus the middleware every request passes through
// (request id, bearer-token check, JSON bodies for httplib's own errors, access log, metrics).
#pragma once

#include <string>

#include <httplib.h>

#include "daemon_context.hpp"
#include "framed_server.hpp"

namespace lghd {

// httplib listens with a backlog of 5 (a constant compiled into Debian's library). A burst of
// clients overflows that queue, and the kernel then drops their handshakes or resets them after
// they sent their request. Listening again on the bound socket raises the backlog. Requests are
// read off their connections by FramedServer, which checks their framing first.
class HttpServer : public FramedServer {
 public:
  bool raiseListenBacklog(int backlog);
};

void configureServer(httplib::Server& server, DaemonContext& context);

// Binds host:port (0: any free port) with a large listen backlog. Returns the port, or -1 when
// it cannot bind.
int bindServer(HttpServer& server, const std::string& host, int port);

}  // namespace lghd
