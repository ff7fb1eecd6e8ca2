#include "context/gl_context.hpp"

#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "gl/software_rasterizer.hpp"
#include "lgh/error.hpp"
#include "lgh/image.hpp"

namespace lgh {
namespace {

void GLAPIENTRY debugCallback(GLenum /*source*/, GLenum type, GLuint id, GLenum severity,
                              GLsizei /*length*/, const GLchar* message, const void* /*user*/) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  // Performance hints (NVIDIA reports every read-back's buffer migration) would drown the log
  // at warning level; they stay visible with --log-level debug.
  auto level = type == GL_DEBUG_TYPE_ERROR         ? spdlog::level::err
               : type == GL_DEBUG_TYPE_PERFORMANCE ? spdlog::level::debug
                                                   : spdlog::level::warn;
  spdlog::log(level, "GL debug [{}]: {}", id, message);
}

std::unique_ptr<GlContext> createBackend(ContextBackend backend, const RendererOptions& options) {
  switch (backend) {
    case ContextBackend::EglDevice:
      return createEglDeviceContext(options);
    case ContextBackend::Surfaceless:
      return createSurfacelessContext(options);
    case ContextBackend::OSMesa:
      return createOsmesaContext(options);
    case ContextBackend::Auto:
      break;
  }
  throw Error(ErrorCode::Internal, "no context backend selected");
}

void checkRequirements(const GlContext& context, const RendererOptions& options) {
  const DeviceInfo& info = context.info();
  if (info.glMajor < 4 || (info.glMajor == 4 && info.glMinor < 5)) {
    throw Error(ErrorCode::Unavailable, fmt::format("OpenGL 4.5 or newer is required; {} gives {}",
                                                    info.contextPath, info.glVersion));
  }
  if (options.requireGpu && info.softwareRenderer) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("a GPU was required but {} gives the software renderer '{}'",
                            info.contextPath, info.glRenderer));
  }
}

}  // namespace

GlContext::~GlContext() = default;

void GlContext::makeCurrent() {
  bindPlatform();
  if (!loaded_) {
    loadFunctions();
    return;
  }
  gl::setCurrentApi(&api_);
}

void GlContext::releaseApi() {
  if (gl::currentApi() == &api_) gl::setCurrentApi(nullptr);
}

void GlContext::loadGl(GLADuserptrloadfunc load, void* userData) {
  const int version = gladLoadGLContextUserPtr(&api_, load, userData);
  if (version == 0) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("{}: the context's proc-address function gave no glGetString, or the "
                            "context reports no OpenGL version",
                            info_.contextPath));
  }
  loaded_ = true;
  gl::setCurrentApi(&api_);
  readGlInfo();
  installDebugOutput();
}

void GlContext::readGlInfo() {
  auto text = [](GLenum name) {
    const auto* value = reinterpret_cast<const char*>(glGetString(name));
    return std::string(value != nullptr ? value : "");
  };
  // Not a property of the context, but every client that reports the device (the renderer, the
  // benchmark) reports it with the GL strings.
  info_.imageBackend = image_io::backendName();
  info_.glVendor = text(GL_VENDOR);
  info_.glRenderer = text(GL_RENDERER);
  info_.glVersion = text(GL_VERSION);
  info_.glslVersion = text(GL_SHADING_LANGUAGE_VERSION);
  glGetIntegerv(GL_MAJOR_VERSION, &info_.glMajor);
  glGetIntegerv(GL_MINOR_VERSION, &info_.glMinor);
  info_.softwareRenderer = gl::softwareRasterizer();  // the passes' own test, one list of names
}

void GlContext::installDebugOutput() {
  if (api_.KHR_debug == 0 && api_.VERSION_4_3 == 0) return;
  glEnable(GL_DEBUG_OUTPUT);
  glDebugMessageCallback(debugCallback, nullptr);
}

std::unique_ptr<GlContext> GlContext::create(const RendererOptions& options) {
  std::vector<ContextBackend> order{options.backend};
  if (options.backend == ContextBackend::Auto) {
    order = {ContextBackend::EglDevice, ContextBackend::Surfaceless, ContextBackend::OSMesa};
  }
  std::string failures;
  for (ContextBackend backend : order) {
    try {
      auto context = createBackend(backend, options);
      checkRequirements(*context, options);
      spdlog::info("GL context: {} | {} | {} | {}", context->info().contextPath,
                   context->info().glVendor, context->info().glRenderer, context->info().glVersion);
      return context;
    } catch (const Error& error) {
      // --require-gpu still falls back between paths (NVIDIA also offers surfaceless EGL);
      // checkRequirements refuses whichever path lands on a software renderer.
      if (options.backend != ContextBackend::Auto) throw;
      spdlog::warn("context path {} failed: {}; falling back", contextBackendName(backend),
                   error.what());
      failures += fmt::format("{}: {}; ", contextBackendName(backend), error.what());
    }
  }
  throw Error(ErrorCode::Unavailable, "no OpenGL context could be created: " + failures);
}

}  // namespace lgh
