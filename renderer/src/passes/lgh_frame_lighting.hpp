// The many-light part of a frame (docs/ARCHITECTURE.md, "One frame", step 3), between the G-buffer
// and the composite:
//   inputs:  LghSettings, the scene (VPLs are sampled on its surfaces), camera, the G-buffer
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
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame_report.hpp"
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

  FloatImage indirect;   // the LGH lighting, linear, top row first
  FloatImage reference;  // the brute-force image (bruteForce)
  // Per pixel, GL order (row 0 at the bottom): F, k samples (position, weight), overdraw.
  std::vector<float> reservoirSums;
  std::vector<glm::vec4> shadowSamples;
  int shadowSampleCount = 0;
  std::vector<std::uint32_t> overdrawCounts;
  LghLevelTable levels;
  LightingPath path = LightingPath::Auto;  // the path that ran
};

class LghFrameLighting {
 public:
  LghFrameLighting();
  ~LghFrameLighting();
  LghFrameLighting(const LghFrameLighting&) = delete;
  LghFrameLighting& operator=(const LghFrameLighting&) = delete;

  void run(const LghSettings& settings, const CachedScene& scene, const CameraMatrices& camera,
           FrameTargets& frame, gl::GpuTimer& timer, FrameReport& report,
           LghFrameProbe* probe = nullptr);

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
  LightingPath choosePath(LightingPath requested, const LghLightingParams& params,
                          const CameraMatrices& camera, FrameTargets& frame, FrameReport& report);
  LightingPath measureFasterPath(const LghLightingParams& params, const CameraMatrices& camera,
                                 FrameTargets& frame);
  void light(LightingPath path, const LghLightingParams& params, const CameraMatrices& camera,
             FrameTargets& frame, gl::GpuTimer& timer);
  void readProbe(const LghSettings& settings, const CameraMatrices& camera, FrameTargets& frame,
                 gl::GpuTimer& timer, LghFrameProbe& probe);

  LghBuilder builder_;
  gl::SizedBuffer vplBuffer_;
  std::optional<VplKey> vplKey_;
  LghLightingTargets targets_;
  LghRasterLightingPass raster_;
  LghComputeLightingPass compute_;
  LghInterleavePass interleave_;
  LghBruteForcePass bruteForce_;
  std::optional<LightingPath> measuredPath_;
  bool sampled_ = false;  // the last run picked shadow samples
};

}  // namespace lgh
