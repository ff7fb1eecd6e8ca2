// The headless OpenGL context: the only code that touches EGL or OSMesa. One context for the life
// of the process; rendering goes to framebuffer objects, never to a window surface. Each context
// resolves its GL functions through its own proc-address function into the table it owns
// (gl/gl_api.hpp), and makes that table current with itself.
#pragma once

#include <memory>
#include <string>

#include "gl/gl_api.hpp"
#include "lgh/device_info.hpp"
#include "lgh/renderer_options.hpp"

namespace lgh {

class GlContext {
 public:
  // Tries the paths that `options.backend` allows, in order egl-device -> surfaceless -> osmesa
  // for Auto; an explicit backend tries only that one. Every fallback taken is logged.
  // Throws lgh::Error(Unavailable) with what each path said when none works.
  static std::unique_ptr<GlContext> create(const RendererOptions& options);

  virtual ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context and its GL functions current on the calling thread (a shared context's first
  // call loads its functions).
  void makeCurrent();
  // A second context in this one's share group, current nowhere yet: buffers, textures, samplers,
  // sync objects and programs are common to both; vertex arrays, framebuffers and queries are
  // not. For work off the render thread (gl/gl_worker.hpp). Throws lgh::Error(Unavailable).
  virtual std::unique_ptr<GlContext> createShared() const = 0;
  // Leaves the calling thread with no current context (a worker thread, before it ends).
  virtual void doneCurrent() = 0;
  const DeviceInfo& info() const { return info_; }
  const gl::Api& api() const { return api_; }

 protected:
  GlContext() = default;
  // The platform's make-current for this context.
  virtual void bindPlatform() = 0;
  // Once current for the first time (a shared context): loadGl with the platform's function.
  virtual void loadFunctions() = 0;
  // Once the context is current for the first time: fills the function table through the
  // platform's proc-address function, makes it current and reads the GL strings into info_.
  void loadGl(GLADuserptrloadfunc load, void* userData);
  // Clears this thread's function table if it is this context's (at destruction).
  void releaseApi();
  DeviceInfo info_;

 private:
  void readGlInfo();
  void installDebugOutput();
  gl::Api api_{};
  bool loaded_ = false;
};

// Creates an EGL context on an EGL device (egl-device) or on Mesa's surfaceless platform
// (context/egl_context.cpp).
std::unique_ptr<GlContext> createEglDeviceContext(const RendererOptions& options);
std::unique_ptr<GlContext> createSurfacelessContext(const RendererOptions& options);
// Creates an OSMesa context (context/osmesa_context.cpp); libOSMesa is loaded at run time.
std::unique_ptr<GlContext> createOsmesaContext(const RendererOptions& options);

}  // namespace lgh
