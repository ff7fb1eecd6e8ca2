// The Vulkan side of shadows (docs/ARCHITECTURE.md "One frame", step 4; docs/SHADOWS.md): the
// Vulkan device that is the GL device, the acceleration structures of a scene, and shadow rays
// traced for a batch of pixels by ray query (a compute shader) or by a ray-tracing pipeline (raygen
// + miss), with identical results. Runs in the renderer's process, on the render thread.
//
// This header sees neither Vulkan nor GL: the frame code (GL) hands rays over in buffers that
// Vulkan owns and shares with GL, either as exported memory that GL imports (interop: nothing
// crosses the CPU) or as host-visible memory that GL copies to and from (staging: the fallback
// where the drivers cannot share, e.g. Mesa's llvmpipe cannot back a GL buffer with lavapipe
// memory).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "lgh/enum_names.hpp"

namespace lgh {
struct Scene;
}

namespace lgh::vk {

enum class TracePath { RayQuery, Pipeline };

using DeviceUuid = std::array<std::uint8_t, 16>;

// What the tracer runs on and can do; reported in /v1/info and the logs.
struct TracerInfo {
  std::string deviceName;            // VkPhysicalDeviceProperties::deviceName
  std::string driverName;            // VkPhysicalDeviceDriverProperties: driverName, driverInfo
  std::string apiVersion;            // "1.3.289"
  bool rayQuery = false;             // VK_KHR_ray_query enabled
  bool rayTracingPipeline = false;   // VK_KHR_ray_tracing_pipeline enabled
  bool externalMemoryFd = false;     // buffers exportable as opaque fds
  bool externalSemaphoreFd = false;  // semaphores exportable as opaque fds
  double createMs = 0.0;             // loader + instance + device + pipelines, wall clock
};

// The acceleration structures of one Scene: a compacted BLAS per mesh (all its primitives,
// opaque, no face culling) and a TLAS over the scene's instances. Owned by the scene cache next
// to the GL upload of the same scene.
class TraceScene {
 public:
  virtual ~TraceScene() = default;
  virtual std::size_t gpuBytes() const = 0;  // device memory held
  // The build's GPU time: BLAS + compaction + TLAS, Vulkan timestamps. A small scene's build is
  // submitted without waiting for it (the traces that use it follow on the same queue): this
  // waits for it. Throws lgh::Error(Internal) when that wait fails.
  virtual double buildGpuMs() const = 0;
  // The same as a function that may outlive the scene: a frame reads it when it is taken.
  virtual std::function<double()> buildGpuMsReader() const = 0;
  virtual std::size_t triangleCount() const = 0;
};

// One frame's shadow rays, laid out per pixel (pixel = y * width + x, any row order the caller
// likes, as long as it is the same for all three buffers):
//   origins    vec4 per pixel: xyz the ray origin (world space, already offset off the surface);
//              w > 0: trace this pixel's rays, else none (their bits stay 0).
//   targets    vec4 per pixel and ray, at [pixel * raysPerPixel + ray]:
//              w == 1: a point; the ray ends short of xyz by TraceParams::endEpsilon (relative);
//              w == 0: a direction (need not be unit length) towards a light at infinity;
//              w <  0: no ray (its bit stays 0).
//   visibility uint32 per pixel and word, at [pixel * words + ray / 32]: bit ray % 32 is set when
//              the ray reached its end unoccluded. Every word of every pixel is written.
// A batch may say where its rays are: the tiles of kRayTileSize x kRayTileSize pixels outside
// which no pixel has rays (origin w <= 0). The ray-query path, which writes zeros to every word
// before it traces, then launches those tiles alone; the ray-tracing pipeline launches every pixel.
inline constexpr std::uint32_t kRayTileSize = 8;
struct RayTiles {
  std::array<std::uint32_t, 2> first{0, 0};  // (column, row) of the first tile
  std::array<std::uint32_t, 2> count{0, 0};  // columns and rows from there on (0: none)
};

struct RayBatchShape {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t raysPerPixel = 0;  // 1..kMaxRaysPerPixel
  std::optional<RayTiles> tiles;   // none: rays anywhere
  std::uint32_t words() const { return (raysPerPixel + 31U) / 32U; }
  std::uint64_t pixels() const { return std::uint64_t{width} * height; }
};
inline constexpr std::uint32_t kMaxRaysPerPixel = 64;

enum class Transport { Interop, Staging };

// Which of the shadow rays' buffer sets (each with its own semaphores) a batch uses: 0 or 1.
using RayLane = std::uint32_t;
inline constexpr RayLane kRayLanes = 2;

// A buffer Vulkan owns, as GL gets to see it.
struct SharedBuffer {
  std::uint64_t size = 0;  // bytes of the buffer
  // Interop: the memory as an opaque fd for glImportMemoryFdEXT (the importer owns it: GL closes
  // it on a successful import; close it yourself otherwise), the size of the memory object
  // (>= size) and whether it is a dedicated allocation (GL_DEDICATED_MEMORY_OBJECT_EXT).
  int fd = -1;
  std::uint64_t allocationSize = 0;
  bool dedicated = false;
  // Staging: host-visible, host-coherent memory, mapped for the buffer's life.
  void* mapped = nullptr;
};

struct RayBuffers {
  Transport transport = Transport::Staging;
  std::uint64_t generation = 0;  // changes whenever the buffers are reallocated
  SharedBuffer origins;
  SharedBuffer targets;
  SharedBuffer visibility;
};

// Interop semaphores as opaque fds for glImportSemaphoreFdEXT (GL owns them after import):
// GL signals `glDone` once the origins and targets are written; Vulkan waits on it, traces and
// signals `vkDone`; GL waits on that before reading the visibility.
struct SemaphoreFds {
  int glDone = -1;
  int vkDone = -1;
};

struct TraceParams {
  float tMin = 0.0F;           // where each ray starts along its direction (world units)
  float tMaxInfinite = 1e30F;  // the length of rays towards lights at infinity
  float endEpsilon = 1e-3F;    // rays to points stop at (1 - endEpsilon) of the distance
};

struct TraceTimings {
  double traceGpuMs = 0.0;  // Vulkan timestamps around the trace
};

// ---- Closest hits: the light paths of GI's VPLs and the path-traced reference (docs/GI.md) ----
// A batch of `rays` rays in two buffers that Vulkan owns and shares with GL like the shadow rays:
//   rays  2 x vec4 per ray: (origin.xyz, tMin), (direction.xyz, tMax); the direction need not be
//         unit length (t is in its units); a ray with !(tMax > tMin) is not traced (a miss).
//   hits  one HitRecord (32 bytes, glsl/include/hit_record.glsl) per ray: t (< 0: a miss), the
//         instance (its index in Scene::instances), the geometry (the primitive's index among
//         its mesh's primitives that have triangles: vk::PackedMesh::primitives), the primitive
//         (the triangle's index among that primitive's kept triangles), the barycentrics of the
//         triangle's vertices 1 and 2, and 1 when the ray met the counter-clockwise side.
// Any: an occlusion query; the record tells a hit (t >= 0) from a miss, nothing more.
enum class HitQuery { Closest, Any };

struct HitBatchShape {
  std::uint32_t rays = 0;
  HitQuery query = HitQuery::Closest;
};
inline constexpr std::uint64_t kHitRayBytes = 32;
inline constexpr std::uint64_t kHitRecordBytes = 32;

struct HitBuffers {
  Transport transport = Transport::Staging;
  std::uint64_t generation = 0;  // changes whenever the buffers are reallocated
  SharedBuffer rays;
  SharedBuffer hits;
};

// ---- Light paths: GI's VPLs, every bounce in one submission (docs/GI.md) ----------------------
// The light paths' emit kernel, then per bounce a closest-hit trace and the bounce kernel
// (glsl/vk/gi_emit.comp, gi_bounce.comp), recorded into one command buffer: the rays, hits and
// paths never leave Vulkan; only the VPL buffer is shared with GL (interop or staging, as the
// batches above). The scene's surfaces as the bounce kernel reads them at hits, as byte arrays in
// the std430 layouts of glsl/include/hit_surface.glsl and gi_material.glsl (renderer/src/gi/
// hit_geometry.hpp packs them); uploaded to the device once per `id`.
struct LightPathScene {
  std::uint64_t id = 0;  // the same id, the same arrays
  std::span<const std::byte> vertices;
  std::span<const std::byte> indices;
  std::span<const std::byte> geometries;
  std::span<const std::byte> instances;
  std::span<const std::byte> materials;
  std::span<const std::byte> albedoTexels;  // packed sRGB RGBA8, 256^2 per layer
};

// One frame's light paths (docs/GI.md, "Light paths"): `paths` paths of `slotsPerPath` VPL slots
// (VPL slot s of path p at [s * paths + p]), slots from paths * slotsPerPath to vplCount cleared.
struct LightPathBatch {
  std::uint32_t paths = 0;
  std::uint32_t vplCount = 0;
  std::uint32_t bounces = 0;  // 1..kMaxLightPathBounces
  std::uint32_t seed = 0;
  bool emissionSlot = false;  // slot 0 of each path: its emission VPL
  float surfaceOffset = 0.0F;
  std::array<float, 4> sceneSphere{};
  std::array<float, 3> sceneMin{};
  std::array<float, 3> sceneMax{};
  std::uint32_t sourceCount = 0;
  std::span<const std::byte> sources;  // GiSource x sourceCount (glsl/include/gi_sources.glsl)
  std::span<const std::byte> lights;   // the frame's Light array (glsl/include/lights.glsl)
};
inline constexpr std::uint32_t kMaxLightPathBounces = 3;

// Bytes of one VPL slot: the PointLight the GL lighting reads (lightgrid/lgh_types.hpp; the GI
// code checks the two agree).
inline constexpr std::uint64_t kVplBytes = 32;

// The VPL buffer (PointLight per slot), shared with GL like the batch buffers.
struct VplBuffers {
  Transport transport = Transport::Staging;
  std::uint64_t generation = 0;  // changes whenever the buffer is reallocated
  SharedBuffer vpls;
};

// Vulkan timestamps of the last submission's steps; all 0 without timestamps.
struct LightPathTimings {
  bool traced = false;
  double totalMs = 0.0;  // the whole submission
  double emitMs = 0.0;   // the inputs' upload, the slots' clear and the emit kernel
  double raysMs = 0.0;   // the traces, summed
  std::array<double, kMaxLightPathBounces> bounceMs{};
};

class ShadowTracer {
 public:
  // Loads libvulkan.so.1 at run time, picks the physical device whose deviceUUID equals
  // `glDevice` (the GL context's GL_DEVICE_UUID_EXT), and creates a device with acceleration
  // structures and every tracing path it offers, and their pipelines. Throws
  // lgh::Error(Unavailable) that says why not: no loader or ICD, no device with that UUID (naming
  // the devices found), no acceleration structures, no tracing path.
  static std::unique_ptr<ShadowTracer> create(const DeviceUuid& glDevice);

  virtual ~ShadowTracer() = default;
  virtual const TracerInfo& info() const = 0;
  bool supports(TracePath path) const {
    return path == TracePath::RayQuery ? info().rayQuery : info().rayTracingPipeline;
  }

  // Builds the acceleration structures from the CPU scene (positions and indices; every
  // instance's world transform). Throws lgh::Error(Internal) on a Vulkan failure.
  virtual std::unique_ptr<TraceScene> buildScene(const Scene& scene) = 0;
  // buildScene for another thread (a scene's prefetch, while the render thread traces): holds
  // the device, not the tracer, so it may outlive the tracer; returns once the build has
  // finished on the GPU (its buildGpuMs() waits for nothing). Throws as buildScene does.
  using SceneBuilder = std::function<std::unique_ptr<TraceScene>(const Scene&)>;
  virtual SceneBuilder sceneBuilder() const = 0;

  // The ray batch buffers of `lane` for `shape`, reallocated (new generation, new fds) only when
  // they must grow or the transport changes. Interop needs info().externalMemoryFd. Each of the
  // kRayLanes lanes has buffers and semaphores of its own, so that one frame's trace may run
  // while GL writes the next frame's rays into the other lane (docs/SHADOWS.md, "Overlapped
  // frames").
  virtual const RayBuffers& rayBuffers(const RayBatchShape& shape, Transport transport,
                                       RayLane lane) = 0;
  const RayBuffers& rayBuffers(const RayBatchShape& shape, Transport transport) {
    return rayBuffers(shape, transport, 0);
  }

  // A fresh pair of exported semaphores for `lane` (needs info().externalSemaphoreFd). Once GL
  // has imported them, trace(..., useSemaphores = true) of that lane waits on and signals the
  // pair last exported.
  virtual SemaphoreFds exportSemaphores(RayLane lane) = 0;
  SemaphoreFds exportSemaphores() { return exportSemaphores(0); }

  // Traces every ray of the batch in `lane`'s buffers as rayBuffers() last returned them. With
  // useSemaphores, the GPU waits for GL's `glDone` and signals `vkDone`, and trace() returns once
  // the work is submitted; otherwise the caller has made the inputs visible (glFinish, or the
  // staging copy) and trace() returns when the GPU has finished. Several traces may run in one
  // frame (the brute-force reference traces its lights in chunks). Throws lgh::Error(Internal)
  // on a Vulkan failure (VK_ERROR_DEVICE_LOST included: the tracer must then be created again).
  virtual void trace(const TraceScene& scene, TracePath path, const RayBatchShape& shape,
                     const TraceParams& params, bool useSemaphores, RayLane lane) = 0;
  void trace(const TraceScene& scene, TracePath path, const RayBatchShape& shape,
             const TraceParams& params, bool useSemaphores) {
    trace(scene, path, shape, params, useSemaphores, 0);
  }

  // trace() without semaphores that returns once the work is submitted, with the trace's number
  // (lastTrace()). The caller has made the inputs visible (the staging copy) and calls
  // awaitTrace() with the number before it reads the visibility: one frame's rays are traced
  // while GL draws the next one where the drivers share no semaphores (Mesa). Throws as trace().
  virtual std::uint64_t submitTrace(const TraceScene& scene, TracePath path,
                                    const RayBatchShape& shape, const TraceParams& params,
                                    RayLane lane) = 0;
  // Returns once the traces numbered `number` and lower have finished on the GPU.
  virtual void awaitTrace(std::uint64_t number) = 0;
  // Whether awaitTrace(number) would return at once: asks the fences, never waits.
  virtual bool traceFinished(std::uint64_t number) = 0;

  // Traces are numbered 1, 2, ... by the tracer: the number of the last trace() (0: none).
  virtual std::uint64_t lastTrace() const = 0;
  // The GPU time of the traces up to and including number `through` that no earlier call
  // returned, summed; waits for those still running, never for later ones. A frame asks for its
  // own when it is taken, so that the next frame is drawn without waiting for this one's rays.
  virtual TraceTimings collectTimingsThrough(std::uint64_t through) = 0;
  // Every trace so far.
  TraceTimings collectTimings() { return collectTimingsThrough(lastTrace()); }

  // Closest hits, with buffers, semaphores and timings of their own (the shadow rays' stay as
  // they are): the same contract as rayBuffers, exportSemaphores, trace and collectTimings.
  virtual const HitBuffers& hitBuffers(std::uint32_t rays, Transport transport) = 0;
  virtual SemaphoreFds exportHitSemaphores() = 0;
  virtual void traceHits(const TraceScene& scene, TracePath path, const HitBatchShape& shape,
                         bool useSemaphores) = 0;
  virtual TraceTimings collectHitTimings() = 0;

  // Light paths, with a buffer, semaphores and timings of their own: the same contract as
  // rayBuffers, exportSemaphores, trace and collectTimings, for the VPL buffer of `vplCount`
  // slots. traceLightPaths waits on GL's `glDone` (GL is done reading the VPLs) and signals
  // `vkDone` (they are written) around its one submission.
  virtual const VplBuffers& vplBuffers(std::uint32_t vplCount, Transport transport) = 0;
  virtual SemaphoreFds exportLightPathSemaphores() = 0;
  virtual void traceLightPaths(const TraceScene& scene, TracePath path,
                               const LightPathScene& surfaces, const LightPathBatch& batch,
                               bool useSemaphores) = 0;
  // As lastTrace / collectTimingsThrough / collectTimings, for the light paths' submissions.
  virtual std::uint64_t lastLightPathTrace() const = 0;
  virtual LightPathTimings collectLightPathTimingsThrough(std::uint64_t through) = 0;
  LightPathTimings collectLightPathTimings() {
    return collectLightPathTimingsThrough(lastLightPathTrace());
  }
};

}  // namespace lgh::vk

template <>
struct lgh::EnumNames<lgh::vk::TracePath> {
  static constexpr std::array<EnumName<vk::TracePath>, 2> names{{
      {"ray-query", vk::TracePath::RayQuery},
      {"pipeline", vk::TracePath::Pipeline},
  }};
};
