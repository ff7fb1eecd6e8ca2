// The path-traced reference of the LGH's indirect light, for small scenes (tests, the benchmark's
// quality runs; never HTTP): ground truth for the VPL approximation (docs/GI.md). Progressive:
// iterations of `samplesPerIteration` camera paths per pixel, wavefront style, each vertex a
// closest-hit batch (the bounce) and an occlusion batch (next-event estimation) on the Vulkan
// tracer, the rest in GL compute (glsl/gi_path_*.comp):
//   x0        the pixel's G-buffer surface; next-event estimation to the emissive triangles only
//             (the analytic lights' direct light is the frame's direct lighting); a bounce from
//             the full BRDF (cosine + GGX mixture)
//   x1..xB    diffuse vertices (base colour x (1 - metallic), as the light paths treat them), each
//             with next-event estimation to every source, then a cosine-weighted bounce
// so it estimates what the light paths' VPLs stand for: area lights' direct light plus 1..B
// diffuse bounces of every light, with exact visibility, no clamp and cosine-weighted emitters.
#pragma once

#include <cstdint>
#include <vector>

#include "gi/gi_source_buffer.hpp"
#include "gi/gi_tracing.hpp"
#include "gl/gl_objects.hpp"
#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"
#include "scene/camera.hpp"
#include "scene/scene_cache.hpp"

namespace lgh {

struct PathTracingSettings {
  int bounces = 3;
  int samplesPerPixel = 64;
  std::uint32_t seed = 1;
  ShadowTracing tracing = ShadowTracing::Auto;
};

struct PathTracingInputs {
  const CachedScene& scene;
  const std::vector<LightDesc>& lights;  // the frame's lights, in the order of lightBuffer
  GLuint lightBuffer = 0;
  const CameraMatrices& camera;
  const FrameTargets& frame;               // its G-buffer: the first vertices
  const std::vector<Material>& materials;  // the frame's (MaterialTable), one per scene material
};

class PathTracedReference {
 public:
  PathTracedReference();
  ~PathTracedReference();
  PathTracedReference(const PathTracedReference&) = delete;
  PathTracedReference& operator=(const PathTracedReference&) = delete;

  // The mean radiance of the samples, top row first; alpha = coverage. Waits for the GPU.
  FloatImage render(const PathTracingSettings& settings, const PathTracingInputs& inputs,
                    GiTracing& tracing);

 private:
  void iterate(const PathTracingSettings& settings, const PathTracingInputs& inputs,
               GiTracing& tracing, const GiTracing::Session& session, std::uint32_t paths,
               std::uint32_t samples, std::uint32_t seed);

  gl::Program start_;
  gl::Program gather_;
  gl::Program vertex_;
  gl::Program accumulate_;
  GiSourceBuffer sources_;
  gl::SizedBuffer paths_;
  gl::SizedBuffer radiance_;
};

}  // namespace lgh
