// What ran a frame: the context path and the GL strings, reported in every result.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace lgh {

struct DeviceInfo {
  std::string contextPath;  // "egl-device", "surfaceless" or "osmesa"
  int eglDeviceIndex = -1;
  int eglDeviceCount = 0;
  std::string glVendor;
  std::string glRenderer;
  std::string glVersion;
  std::string glslVersion;
  int glMajor = 0;
  int glMinor = 0;
  bool softwareRenderer = false;
  // A robust context (reset notification): a GPU reset fails the frame and the renderer is made
  // again, instead of hanging.
  bool robustContext = false;
  std::string imageBackend;  // "oiio" or "lean"
  nlohmann::json toJson() const;
};

}  // namespace lgh
