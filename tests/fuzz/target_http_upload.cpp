#include <cstring>
#include <string>
#include <string_view>

#include <httplib.h>

#include "api_error.hpp"
#include "fuzz_targets.hpp"
#include "http_framing.hpp"
#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "uploads.hpp"

namespace lgh::fuzz {
namespace {

// The request bytes as httplib reads them; what it writes back is dropped.
class MemoryStream : public httplib::Stream {
 public:
  explicit MemoryStream(std::string_view input) : input_(input) {}
  bool is_readable() const override { return position_ < input_.size(); }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const std::size_t count = std::min(size, input_.size() - position_);
    std::memcpy(ptr, input_.data() + position_, count);
    position_ += count;
    return static_cast<ssize_t>(count);
  }
  ssize_t write(const char* /*ptr*/, size_t size) override { return static_cast<ssize_t>(size); }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 40000;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 8080;
  }
  socket_t socket() const override { return 0; }

 private:
  std::string_view input_;
  std::size_t position_ = 0;
};

// What POST /v1/render does with an upload before it queues a render (routes_render.cpp).
void parseUpload(const httplib::Request& http) {
  const nlohmann::json json = lghd::requestPartJson(http);
  const std::vector<lghd::UploadedFile> files = lghd::uploadedFiles(http);
  RenderRequest request = parseRenderRequest(json);
  if (!files.empty()) request.scene = lghd::uploadedScene(files);
}

class Harness : public httplib::Server {
 public:
  Harness() {
    set_payload_max_length(std::size_t{4} << 20U);
    Post("/v1/render", [](const httplib::Request& http, httplib::Response& response) {
      try {
        if (http.is_multipart_form_data()) {
          parseUpload(http);
        } else {
          (void)parseRenderRequest(http.body.empty() ? std::string("{}") : http.body);
        }
        response.status = 200;
      } catch (const lghd::ApiError& error) {
        response.status = error.status();
      } catch (const Error& error) {
        response.status = lghd::httpStatus(error.code());
      }
    });
  }

  void serve(std::string_view bytes) {
    MemoryStream stream(bytes);
    bool connectionClosed = false;
    process_request(stream, true, connectionClosed, nullptr);
  }
};

}  // namespace

void httpUpload(const std::uint8_t* data, std::size_t size) {
  static Harness harness;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::size_t headEnd = lghd::findHeadEnd(bytes);
  if (headEnd == std::string_view::npos) return;
  const lghd::FramingLimits limits;
  if (std::holds_alternative<lghd::FramingError>(
          lghd::checkRequestHead(bytes.substr(0, headEnd), limits))) {
    return;
  }
  harness.serve(bytes);
}

}  // namespace lgh::fuzz
