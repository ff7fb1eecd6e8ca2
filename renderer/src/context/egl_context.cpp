// EGL contexts: on an EGL device (EGL_EXT_platform_device: NVIDIA, Mesa's software device) or on
// Mesa's surfaceless platform. libEGL is opened at run time by glad's EGL loader, so a machine
// without it still starts and can take the OSMesa path.
#include <glad/egl.h>

#include <cstring>
#include <map>
#include <mutex>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "context/container_hints.hpp"
#include "context/gl_context.hpp"
#include "lgh/egl_devices.hpp"
#include "lgh/error.hpp"

namespace lgh {
namespace {

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t length = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
    const bool startOk = p == list || p[-1] == ' ';
    const bool endOk = p[length] == ' ' || p[length] == '\0';
    if (startOk && endOk) return true;
  }
  return false;
}

std::string eglErrorName(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS (the device is in use or not accessible: a wrong GPU index, a MIG "
             "slice, or a container without graphics capability)";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return fmt::format("EGL error 0x{:x}", error);
  }
}

[[noreturn]] void failEgl(const std::string& what) {
  throw Error(ErrorCode::Unavailable,
              fmt::format("{} failed: {}", what, eglErrorName(eglGetError())));
}

// Opens libEGL and resolves the client-level functions (core EGL, the device and platform
// extensions), once per process. Display-level functions of EGL 1.2+ (eglBindAPI, ...) are
// resolved again once a display is initialized: glad reads the version from the display.
void loadEglClient() {
  static std::once_flag once;
  static int version = 0;
  std::call_once(once, [] { version = gladLoaderLoadEGL(EGL_NO_DISPLAY); });
  if (version == 0) {
    throw Error(ErrorCode::Unavailable,
                "libEGL.so.1 could not be loaded (install the GL vendor's EGL, e.g. Debian's "
                "libegl1 with libegl-mesa0, or NVIDIA's driver; or use --backend osmesa)");
  }
}

// An EGL display is one per device and process: every context on it shares its initialization,
// and eglTerminate would end it for all of them. Counted here, terminated with its last context.
class DisplayUsers {
 public:
  static void acquire(EGLDisplay display) {
    std::lock_guard lock(mutex());
    ++counts()[display];
  }
  // True when `display` has no other user left (the caller terminates it).
  static bool release(EGLDisplay display) {
    std::lock_guard lock(mutex());
    auto it = counts().find(display);
    if (it == counts().end() || --it->second > 0) return false;
    counts().erase(it);
    return true;
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static std::map<EGLDisplay, int>& counts() {
    static std::map<EGLDisplay, int> c;
    return c;
  }
};

GLADapiproc eglProcAddress(void* /*userData*/, const char* name) {
  return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name));
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, const std::string& path, const RendererOptions& options)
      : display_(display) {
    info_.contextPath = path;
    EGLint major = 0;
    EGLint minor = 0;
    if (eglInitialize(display_, &major, &minor) != EGL_TRUE) failEgl("eglInitialize");
    DisplayUsers::acquire(display_);
    initialized_ = true;
    if (gladLoaderLoadEGL(display_) == 0) failEgl("loading EGL functions for the display");
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) failEgl("eglBindAPI(EGL_OPENGL_API)");
    createContext(options.glDebug, major > 1 || (major == 1 && minor >= 5));
    bindPlatform();
    loadGl(eglProcAddress, nullptr);
  }

  // A context in `share`'s share group, with its config and attributes (EGL requires the same
  // reset notification strategy), made current later by the thread that uses it.
  struct Sharing {};
  EglContext(const EglContext& share, Sharing /*tag*/)
      : display_(share.display_), config_(share.config_), attributes_(share.attributes_) {
    info_ = share.info_;
    info_.contextPath = share.info_.contextPath + " (shared)";
    DisplayUsers::acquire(display_);
    initialized_ = true;
    context_ = eglCreateContext(display_, config_, share.context_, attributes_.data());
    if (context_ == EGL_NO_CONTEXT) failEgl("eglCreateContext (sharing the renderer's objects)");
  }

  ~EglContext() override {
    releaseApi();
    if (context_ != EGL_NO_CONTEXT) {
      // Destroying a shared context on the render thread must leave the render thread's own
      // context current.
      unbindIfCurrent();
      eglDestroyContext(display_, context_);
    }
    if (initialized_ && DisplayUsers::release(display_)) eglTerminate(display_);
  }

  std::unique_ptr<GlContext> createShared() const override {
    return std::make_unique<EglContext>(*this, Sharing{});
  }
  void doneCurrent() override {
    releaseApi();
    unbindIfCurrent();
    eglReleaseThread();
  }

  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void setEglDevice(int index, int count) {
    info_.eglDeviceIndex = index;
    info_.eglDeviceCount = count;
  }

 protected:
  void bindPlatform() override {
    if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
      failEgl("eglMakeCurrent (surfaceless)");
    }
  }
  void loadFunctions() override { loadGl(eglProcAddress, nullptr); }

 private:
  // Leaves the calling thread without a context if this one is current on it (another thread's
  // binding, or another context of this thread, is left alone).
  void unbindIfCurrent() {
    if (eglGetCurrentContext() == context_) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
  }

  // The ways to ask for a robust context with reset notification, best first: EGL 1.5's core
  // attributes (NVIDIA's EGL accepts only these for desktop GL), then EGL_EXT_create_context_
  // robustness's (Mesa), then none (not every driver offers one).
  struct Robustness {
    const char* name;
    std::vector<EGLint> attributes;
  };
  static std::vector<Robustness> robustnessVariants(bool egl15, const char* extensions) {
    std::vector<Robustness> variants;
    if (egl15) {
      variants.push_back(
          {"EGL 1.5 robust access",
           {EGL_CONTEXT_OPENGL_ROBUST_ACCESS, EGL_TRUE,
            EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY, EGL_LOSE_CONTEXT_ON_RESET}});
    }
    if (hasExtension(extensions, "EGL_EXT_create_context_robustness")) {
      variants.push_back(
          {"EGL_EXT_create_context_robustness",
           {EGL_CONTEXT_OPENGL_ROBUST_ACCESS_EXT, EGL_TRUE,
            EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT, EGL_LOSE_CONTEXT_ON_RESET_EXT}});
    }
    variants.push_back({"", {}});
    return variants;
  }

  void createContext(bool debug, bool egl15) {
    const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
    if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
      throw Error(ErrorCode::Unavailable, "EGL display lacks EGL_KHR_surfaceless_context");
    }
    config_ = chooseConfig(extensions);
    // A robust context (GL_KHR_robustness) reports a GPU reset instead of hanging on it: the
    // renderer then fails the frame and is made again.
    const std::vector<Robustness> variants = robustnessVariants(egl15, extensions);
    // Ask for 4.6 core; Mesa's llvmpipe stops at 4.5, which has everything we use.
    for (int minor : {6, 5}) {
      for (const Robustness& robustness : variants) {
        std::vector<EGLint> attributes{
            EGL_CONTEXT_MAJOR_VERSION,       4,
            EGL_CONTEXT_MINOR_VERSION,       minor,
            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
        if (debug) attributes.insert(attributes.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
        attributes.insert(attributes.end(), robustness.attributes.begin(),
                          robustness.attributes.end());
        attributes.push_back(EGL_NONE);
        context_ = eglCreateContext(display_, config_, EGL_NO_CONTEXT, attributes.data());
        const bool robust = !robustness.attributes.empty();
        if (context_ != EGL_NO_CONTEXT) {
          attributes_ = std::move(attributes);
          info_.robustContext = robust;
          if (robust) spdlog::info("robust GL context ({})", robustness.name);
          return;
        }
        spdlog::info("no OpenGL 4.{} core context{} on {} ({})", minor,
                     robust ? fmt::format(" with {}", robustness.name) : "", info_.contextPath,
                     eglErrorName(eglGetError()));
      }
    }
    throw Error(ErrorCode::Unavailable,
                fmt::format("no OpenGL 4.5+ core context on {}", info_.contextPath));
  }

  EGLConfig chooseConfig(const char* extensions) {
    const EGLint attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (eglChooseConfig(display_, attributes, &config, 1, &count) == EGL_TRUE && count > 0) {
      return config;
    }
    if (hasExtension(extensions, "EGL_KHR_no_config_context")) return EGL_NO_CONFIG_KHR;
    throw Error(ErrorCode::Unavailable, "no EGL config renders OpenGL on " + info_.contextPath);
  }

  EGLDisplay display_;
  EGLConfig config_ = nullptr;
  std::vector<EGLint> attributes_;  // the context's, for contexts that share its objects
  EGLContext context_ = EGL_NO_CONTEXT;
  bool initialized_ = false;
};

std::vector<EGLDeviceEXT> queryEglDevices() {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  // NVIDIA's EGL (through glvnd) advertises EGL_EXT_device_base, the union of
  // EGL_EXT_device_enumeration and EGL_EXT_device_query, instead of the two separately.
  const bool enumeration = hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
                           hasExtension(clientExtensions, "EGL_EXT_device_base");
  if (!hasExtension(clientExtensions, "EGL_EXT_platform_device") || !enumeration ||
      eglQueryDevicesEXT == nullptr) {
    throw Error(
        ErrorCode::Unavailable,
        fmt::format("EGL has no EGL_EXT_platform_device with EGL_EXT_device_enumeration "
                    "or EGL_EXT_device_base (is the vendor's EGL ICD JSON installed? In "
                    "containers, NVIDIA_DRIVER_CAPABILITIES must include 'graphics'); "
                    "client extensions: {}{}",
                    clientExtensions != nullptr ? clientExtensions : "none", eglDeviceHints()));
  }
  EGLint count = 0;
  if (eglQueryDevicesEXT(0, nullptr, &count) != EGL_TRUE) failEgl("eglQueryDevicesEXT");
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count) != EGL_TRUE) {
    failEgl("eglQueryDevicesEXT");
  }
  devices.resize(static_cast<size_t>(count));
  return devices;
}

std::string describeDevice(EGLDeviceEXT device) {
  const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
  std::string kind = hasExtension(extensions, "EGL_MESA_device_software") ? "software" : "hardware";
  if (hasExtension(extensions, "EGL_EXT_device_drm")) {
    const char* node = eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT);
    if (node != nullptr) kind += std::string(", ") + node;
  }
  return kind;
}

}  // namespace

int eglDeviceCount() {
  loadEglClient();
  return static_cast<int>(queryEglDevices().size());
}

std::unique_ptr<GlContext> createEglDeviceContext(const RendererOptions& options) {
  loadEglClient();
  auto devices = queryEglDevices();
  for (size_t i = 0; i < devices.size(); ++i) {
    spdlog::info("EGL device {}: {}", i, describeDevice(devices[i]));
  }
  if (options.gpuIndex < 0 || static_cast<size_t>(options.gpuIndex) >= devices.size()) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("GPU index {} out of range: EGL lists {} device(s){}", options.gpuIndex,
                            devices.size(), eglDeviceHints()));
  }
  EGLDeviceEXT device = devices[static_cast<size_t>(options.gpuIndex)];
  EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
  if (display == EGL_NO_DISPLAY) failEgl("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT)");
  auto context = std::make_unique<EglContext>(display, "egl-device", options);
  context->setEglDevice(options.gpuIndex, static_cast<int>(devices.size()));
  return context;
}

std::unique_ptr<GlContext> createSurfacelessContext(const RendererOptions& options) {
  loadEglClient();
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
    throw Error(ErrorCode::Unavailable, "EGL has no EGL_MESA_platform_surfaceless");
  }
  EGLDisplay display =
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) failEgl("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
  return std::make_unique<EglContext>(display, "surfaceless", options);
}

}  // namespace lgh
