// The headless OpenGL context: the only code that touches EGL (or OSMesa). One context for the
// life of the process; rendering goes to framebuffer objects, never to a window surface.
#pragma once

#include <memory>
#include <string>

#include "lgh/device_info.hpp"
#include "lgh/renderer_options.hpp"

namespace lgh {

class GlContext {
 public:
  // Tries the paths that `options.backend` allows, in order egl-device -> surfaceless -> osmesa
  // for Auto; an explicit backend tries only that one. Every fallback taken is logged.
  // Throws lgh::Error(Unavailable) with what each path said when none works.
  static std::unique_ptr<GlContext> create(const RendererOptions& options);

  virtual ~GlContext() = default;
  virtual void makeCurrent() = 0;
  const DeviceInfo& info() const { return info_; }

 protected:
  GlContext() = default;
  // Fills the GL strings of info_ from the current context.
  void readGlInfo();
  DeviceInfo info_;
};

}  // namespace lgh
