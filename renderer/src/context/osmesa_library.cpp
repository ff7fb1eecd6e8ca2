#include "context/osmesa_library.hpp"

#include <dlfcn.h>

#include <mutex>
#include <string>

#include <fmt/format.h>

#include "lgh/error.hpp"

#if LGH_OSMESA
#include <GL/osmesa.h>
#endif

namespace lgh::osmesa {

#if LGH_OSMESA
namespace {

struct Library {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
  std::string error;
};

template <typename Function>
void resolve(void* handle, const char* name, Function& out, std::string& error) {
  out = reinterpret_cast<Function>(dlsym(handle, name));
  if (out == nullptr && error.empty()) error = fmt::format("libOSMesa has no {}", name);
}

// Opened once and kept for the life of the process: Mesa's state lives in it.
const Library& library() {
  static Library lib;
  static std::once_flag once;
  std::call_once(once, [] {
    void* handle = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      lib.error = fmt::format(
          "libOSMesa.so.8 could not be loaded ({}): install Debian's libosmesa6 (Mesa up to "
          "25.0; Mesa 25.1 removed OSMesa, where --backend surfaceless is the software path)",
          dlerror());
      return;
    }
    resolve(handle, "OSMesaCreateContextAttribs", lib.createContextAttribs, lib.error);
    resolve(handle, "OSMesaMakeCurrent", lib.makeCurrent, lib.error);
    resolve(handle, "OSMesaDestroyContext", lib.destroyContext, lib.error);
    resolve(handle, "OSMesaGetProcAddress", lib.getProcAddress, lib.error);
  });
  if (!lib.error.empty()) throw Error(ErrorCode::Unavailable, lib.error);
  return lib;
}

}  // namespace

Context::Context(int major, int minor, const Context* share) : major_(major), minor_(minor) {
  const Library& lib = library();
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            major,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            minor,
                            0};
  context_ = lib.createContextAttribs(
      attributes, share != nullptr ? static_cast<OSMesaContext>(share->context_) : nullptr);
  if (context_ == nullptr) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("OSMesaCreateContextAttribs gave no OpenGL {}.{} core context{}", major,
                            minor, share != nullptr ? " sharing the renderer's objects" : ""));
  }
}

Context::~Context() {
  if (context_ != nullptr) library().destroyContext(static_cast<OSMesaContext>(context_));
}

void Context::makeCurrent() {
  if (library().makeCurrent(static_cast<OSMesaContext>(context_), buffer_, GL_UNSIGNED_BYTE, 1,
                            1) == 0) {
    throw Error(ErrorCode::Unavailable, "OSMesaMakeCurrent failed");
  }
}

void Context::releaseCurrent() { library().makeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0); }

void* Context::procAddress(const char* name) {
  return reinterpret_cast<void*>(library().getProcAddress(name));
}

bool compiledIn() { return true; }

#else  // !LGH_OSMESA

Context::Context(int /*major*/, int /*minor*/, const Context* /*share*/) {
  throw Error(ErrorCode::Unavailable,
              "this build has no OSMesa path (configured with -DLGH_OSMESA=OFF)");
}
Context::~Context() = default;
void Context::makeCurrent() {}
void Context::releaseCurrent() {}
void* Context::procAddress(const char* /*name*/) { return nullptr; }
bool compiledIn() { return false; }

#endif

}  // namespace lgh::osmesa
