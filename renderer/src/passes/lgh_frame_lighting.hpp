// The many-light part of a frame (docs/ARCHITECTURE.md, "One frame", step 3), between the G-buffer
// and the composite:
//   inputs:  LghSettings, the scene, camera, the G-buffer; the VPLs come from light paths
//            (settings.gi, gi/vpl_tracer.hpp) or, as a benchmark mode, from random points on the
//            scene's surfaces
//   outputs: FrameTargets::indirect (unshadowed LGH lighting), the per-pixel shadow samples in
//            LghLightingTargets, timing rows ("lgh build" and the builder's steps, "lgh lighting",
//            "lgh interleave split", "lgh interleave composite") and the FrameReport's decisions
//            ("lgh_lighting" raster|compute, "lgh_lighting_choice", "interleave", "vpls", ...)
// It owns the VPL buffer (cached per scene, count, seed and intensity), the builder, the lighting
// passes, and the choice of path: configured by the request, or for `auto` measured once on the
// first frame that needs it (both paths timed with GPU timers, the faster kept for the life of
// the renderer), except on software rasterizers, where the compute path is taken by rule.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame_report.hpp"
#include "gi/path_traced_reference.hpp"
#include "gi/vpl_tracer.hpp"
#include "gl/gpu_timer.hpp"
#include "lightgrid/lgh_builder.hpp"
#include "passes/lgh_bruteforce_pass.hpp"
#include "passes/lgh_compute_lighting_pass.hpp"
#include "passes/lgh_interleave_pass.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "passes/lgh_raster_lighting_pass.hpp"
#include "scene/scene_cache.hpp"

namespace lgh {

// Extra outputs of one LGH frame, for tests and the benchmark (never exposed over HTTP).
struct LghFrameProbe {
  bool bruteForce = false;  // also render the brute-force reference of the same frame
  bool overdraw = false;    // count fragments (raster) / lights evaluated (compute) per pixel
  bool readBack = true;     // fill the outputs below (waits for the GPU)
  bool readVpls = false;    // read the VPLs back into `vpls`
  // The brute-force reference's own clamp of the VPL singularity, max(d^2, d_min^2):
  //   Hierarchy  d_min = h_1, the LGH's (isolates the hierarchy's error from the clamp's);
  //   Fixed      d_min = referenceMinDistance (world units; 0: no clamp at all).
  enum class ReferenceClamp { Hierarchy, Fixed };
  ReferenceClamp referenceClamp = ReferenceClamp::Hierarchy;
  float referenceMinDistance = 0.0F;
  // Shadowed reference: one ray per VPL and pixel (set by the frame when shadowedReference).
  bool shadowedReference = false;
  PointLightVisibility visibility;
  // The path-traced reference (settings.gi frames only): samples per pixel, 0 for none.
  int pathTracedSamples = 0;
  bool readGBuffer = false;  // fill `gbuffer` (for CPU references)
  // Compile the lighting kernels for every material model and layer, not only the frame's (to
  // compare the specialised kernels with the generic one).
  bool genericBrdf = false;

  FloatImage indirect;    // the LGH lighting, linear, top row first
  FloatImage reference;   // the brute-force image (bruteForce)
  FloatImage pathTraced;  // the path-traced reference (pathTracedSamples > 0)
  // Per pixel, GL order (row 0 at the bottom): F, k samples (position, weight), overdraw.
  std::vector<float> reservoirSums;
  std::vector<glm::vec4> shadowSamples;
  int shadowSampleCount = 0;
  std::vector<std::uint32_t> overdrawCounts;
  LghLevelTable levels;
  LightingPath path = LightingPath::Auto;  // the path that ran
  std::vector<PointLight> vpls;            // readVpls
  VplLayout vplLayout;                     // how the light paths filled them (settings.gi)
  // Filled by FramePipeline: the filtered LGH shadow ratio (1 where the frame has none) and the
  // G-buffer's material (metallic, roughness) per pixel, top row first like the images.
  FloatImage shadowRatio;
  std::vector<glm::vec2> metallicRoughness;
  // readGBuffer: what the lighting read per pixel, top row first.
  struct GBuffer {
    std::vector<glm::vec4> position;   // w: coverage
    std::vector<glm::vec3> normal;     // as stored (fp16)
    std::vector<glm::vec3> baseColor;  // linear (the sRGB target decoded)
    glm::vec3 cameraPosition{0.0F};
  } gbuffer;
};

// What a frame with settings.gi gives the LGH part: the settings, the frame's lights (the light
// paths' sources) and where rays are traced.
struct LghGiInputs {
  const GiSettings& settings;
  const std::vector<LightDesc>& lights;
  GLuint lightBuffer = 0;
  ShadowTracing tracing = ShadowTracing::Auto;
  GiTracing& tracer;
  const std::vector<Material>& materials;  // the frame's (MaterialTable): light paths' albedo
};

class LghFrameLighting {
 public:
  LghFrameLighting();
  ~LghFrameLighting();
  LghFrameLighting(const LghFrameLighting&) = delete;
  LghFrameLighting& operator=(const LghFrameLighting&) = delete;

  // `brdf`: the material models and layers of the frame's G-buffer (brdfFeatures()), which the
  // lighting kernels are compiled for.
  void run(const LghSettings& settings, const CachedScene& scene, const CameraMatrices& camera,
           const BrdfFeatures& brdf, FrameTargets& frame, gl::GpuTimer& timer, FrameReport& report,
           LghFrameProbe* probe = nullptr, const LghGiInputs* gi = nullptr);

  // Adds the writer of the last run's rows that come after the GL timer (the light paths' Vulkan
  // time) to report.lateRows.
  void collectTimings(FrameReport& report);

  // The k shadow samples per pixel that the last run picked (vec4(position, weight) at
  // [pixel * k + s], GL row order), for the shadow rays; {0, 0} when it lit nothing.
  struct ShadowSamples {
    GLuint buffer = 0;
    int count = 0;
  };
  ShadowSamples shadowSamples() const;

  // Total intensity of the VPLs of a scene: vplIntensity x R^2 with R half the scene's bounding
  // diagonal, so that the indirect light's brightness does not depend on the scene's units.
  static float vplTotalIntensity(const Scene& scene, float vplIntensity);

 private:
  struct VplKey {
    const CachedScene* scene = nullptr;
    std::string name;
    std::size_t triangles = 0;
    int count = 0;
    std::uint32_t seed = 0;
    float flux = 0.0F;
    bool operator==(const VplKey&) const = default;
  };

  void uploadVpls(const LghSettings& settings, const CachedScene& scene);
  void traceVpls(const LghGiInputs& gi, const CachedScene& scene, gl::GpuTimer& timer,
                 FrameReport& report);
  LightingPath choosePath(LightingPath requested, const LghLightingParams& params,
                          const CameraMatrices& camera, FrameTargets& frame, FrameReport& report);
  LightingPath measureFasterPath(const LghLightingParams& params, const CameraMatrices& camera,
                                 FrameTargets& frame);
  void light(LightingPath path, const LghLightingParams& params, const CameraMatrices& camera,
             FrameTargets& frame, gl::GpuTimer& timer);
  void readProbe(const LghLightingParams& params, const CameraMatrices& camera, FrameTargets& frame,
                 gl::GpuTimer& timer, LghFrameProbe& probe, const CachedScene& scene,
                 const LghGiInputs* gi);

  LghBuilder builder_;
  gl::SizedBuffer vplBuffer_;
  int vplCount_ = 0;  // this frame's VPLs (slots) in vplBuffer_
  std::optional<VplKey> vplKey_;
  std::unique_ptr<VplTracer> vplTracer_;
  std::unique_ptr<PathTracedReference> pathTracer_;
  GiTracing* giTracing_ = nullptr;  // of the last frame with light paths
  VplLayout vplLayout_;
  LghLightingTargets targets_;
  LghRasterLightingPass raster_;
  LghComputeLightingPass compute_;
  LghInterleavePass interleave_;
  LghBruteForcePass bruteForce_;
  std::optional<LightingPath> measuredPath_;
  bool sampled_ = false;  // the last run picked shadow samples
};

}  // namespace lgh
