// The renderer's public API: a Renderer owns one headless GL context and turns a validated
// RenderRequest into a linear image plus a timing table. The daemon, the CLI and the benchmark are
// thin clients of this header; none of them sees GL.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "lgh/timing.hpp"

namespace lgh {

enum class ContextBackend { Auto, EglDevice, Surfaceless, OSMesa };
// "auto", "egl-device", "surfaceless", "osmesa"; throws lgh::Error(BadRequest) otherwise.
ContextBackend parseContextBackend(const std::string& name);
const char* contextBackendName(ContextBackend backend);

struct RendererOptions {
  ContextBackend backend = ContextBackend::Auto;
  int gpuIndex = 0;         // EGL device index (EGL's order, not CUDA's)
  bool requireGpu = false;  // fail instead of running on a software rasterizer
  bool glDebug = false;     // KHR_debug context; messages go to the log either way
  std::filesystem::path assetRoot = ".";
  std::size_t maxTriangles = 20'000'000;
  int maxTextureSize = 16384;
  std::size_t sceneCacheBytes = 512ULL << 20;  // GPU memory budget of the scene cache
};

// What ran the frame: reported in every result.
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
  std::string imageBackend;  // "oiio" or "lean"
  nlohmann::json toJson() const;
};

struct RenderResult {
  FloatImage image;  // linear RGBA, alpha 0 where nothing was drawn
  TimingTable timings;
  DeviceInfo device;
  std::map<std::string, std::string> paths;  // decisions taken: lighting path, cache, ...
  std::vector<std::string> warnings;
  bool sceneCacheHit = false;
  std::vector<std::uint8_t> encoded;  // the image in the request's output format
  std::string mimeType;

  // Attributes written into PNG/EXR files: renderer string, context path, timings.
  ImageMetadata metadata() const;
  // The image encoded in `output`'s format.
  std::vector<std::uint8_t> encode(const OutputSettings& output) const;
  // {timings, device, paths, warnings} as JSON (no image).
  nlohmann::json summaryJson() const;
};

class Renderer {
 public:
  // Creates the GL context on the calling thread; that thread must make every later call.
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Throws lgh::Error: NotFound/Invalid/TooLarge for bad scenes, Internal for GL failures.
  RenderResult render(const RenderRequest& request);

  const DeviceInfo& device() const;
  const RendererOptions& options() const;

  struct CacheStats {
    std::uint64_t hits = 0;
    std::uint64_t misses = 0;
    std::size_t entries = 0;
    std::size_t bytes = 0;
  };
  CacheStats sceneCacheStats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace lgh
