// The OSMesa context path: Mesa's off-screen library, for machines without EGL (older HPC nodes).
// Upstream Mesa removed OSMesa in 25.1; EGL surfaceless is the lasting software path.
#include <memory>

#include <spdlog/spdlog.h>

#include "context/gl_context.hpp"
#include "context/osmesa_library.hpp"
#include "lgh/error.hpp"

namespace lgh {
namespace {

GLADapiproc osmesaProcAddress(void* /*userData*/, const char* name) {
  return reinterpret_cast<GLADapiproc>(osmesa::Context::procAddress(name));
}

class OsmesaContext final : public GlContext {
 public:
  explicit OsmesaContext(int minor) : context_(4, minor) {
    info_.contextPath = "osmesa";
    bindPlatform();
    loadGl(osmesaProcAddress, nullptr);
  }
  // A context sharing `share`'s objects, made current later by the thread that uses it.
  explicit OsmesaContext(const osmesa::Context& share)
      : context_(share.major(), share.minor(), &share) {
    info_.contextPath = "osmesa (shared)";
  }
  ~OsmesaContext() override { releaseApi(); }
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  std::unique_ptr<GlContext> createShared() const override {
    return std::make_unique<OsmesaContext>(context_);
  }
  void doneCurrent() override {
    releaseApi();
    osmesa::Context::releaseCurrent();
  }

 protected:
  void bindPlatform() override { context_.makeCurrent(); }
  void loadFunctions() override { loadGl(osmesaProcAddress, nullptr); }

 private:
  osmesa::Context context_;
};

}  // namespace

std::unique_ptr<GlContext> createOsmesaContext(const RendererOptions& options) {
  if (options.glDebug) spdlog::info("osmesa: no debug context flag; GL_KHR_debug output is on");
  // Ask for 4.6 core; Mesa's llvmpipe stops at 4.5, which has everything we use.
  try {
    return std::make_unique<OsmesaContext>(6);
  } catch (const Error& error) {
    spdlog::info("osmesa: {}; trying OpenGL 4.5", error.what());
  }
  return std::make_unique<OsmesaContext>(5);
}

}  // namespace lgh
