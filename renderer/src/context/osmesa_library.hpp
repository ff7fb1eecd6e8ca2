// Mesa's off-screen GL library, opened at run time (libOSMesa.so.8): lghd neither links it nor
// needs it unless the osmesa path is taken. Kept apart from the GL loader because <GL/osmesa.h>
// brings in <GL/gl.h>, which must not meet the generated GL header in one translation unit.
#pragma once

namespace lgh::osmesa {

// An OSMesa core-profile context that renders into a 1x1 colour buffer of its own (lghd draws
// into framebuffer objects; the buffer is only what OSMesaMakeCurrent needs).
class Context {
 public:
  // Throws lgh::Error(Unavailable) when the library is missing or gives no such context. With
  // `share`, the context shares its objects (buffers, textures, samplers, programs) with it.
  Context(int major, int minor, const Context* share = nullptr);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  void makeCurrent();
  // Leaves the calling thread with no current OSMesa context.
  static void releaseCurrent();
  int major() const { return major_; }
  int minor() const { return minor_; }
  // OSMesaGetProcAddress: every GL function the library offers, context-independent.
  static void* procAddress(const char* name);

 private:
  void* context_ = nullptr;
  int major_ = 0;
  int minor_ = 0;
  unsigned char buffer_[4] = {};
};

// Whether this build can take the OSMesa path at all (LGH_OSMESA at configure time).
bool compiledIn();

}  // namespace lgh::osmesa
