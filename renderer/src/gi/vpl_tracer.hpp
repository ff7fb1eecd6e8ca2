// Virtual point lights by light tracing (docs/GI.md; the paper's Sec. 4: "tracing light rays up
// to three diffuse bounces"), on the GPU, into the buffer the LGH build reads. Every step runs on
// the Vulkan tracer in one submission (vk/shadow_tracer.hpp, "Light paths"), handed to and from
// GL once per frame (VplTransport):
//   gi emit      a path per slot group: a light source picked by power, the first ray, the
//                path's flux, and for an emissive triangle its emission VPL
//   per bounce:  rays (closest hits) -> gi bounce: the hit resolved into a surface point, a VPL
//                there (flux x albedo / 2 pi), the next ray (cosine-weighted, flux x albedo)
//                before the last bounce
// then GL copies the VPLs into the LGH build's buffer.
// Layout: N = vpl_count slots, S = bounces (+1 when an emissive triangle emits) slots per path,
// P = N / S paths; VPL slot s of path p is vpls[s * P + p]. A path that leaves the scene leaves
// dark slots (zero intensity: the build ignores them), as do the N - P S slots left over. No
// Russian roulette: every path's slots are written every frame, and the same seed, lights and
// scene give the same VPLs whichever tracing path traces them.
//   inputs:  GiSettings, the frame's lights, the scene (its hit geometry and acceleration
//            structures, built on first use), the shadow path setting
//   outputs: the VPL buffer (PointLight x N), timing rows (collectTimings: "gi vpls" with "gi
//            emit", "gi bounce <b>" and "gi rays" inside, from the submission's Vulkan
//            timestamps; the CPU "gi transfer"), decisions ("gi_paths", "gi_slots_per_path",
//            "gi_tracing", "gi_transport"), warnings (no light to trace, too few slots)
#pragma once

#include <cstdint>
#include <vector>

#include "frame_report.hpp"
#include "gi/gi_tracing.hpp"
#include "gl/gl_objects.hpp"
#include "gl/gpu_timer.hpp"
#include "lgh/request.hpp"
#include "passes/light_buffer.hpp"
#include "scene/scene_cache.hpp"

namespace lgh {

struct VplTracingInputs {
  const GiSettings& settings;
  const std::vector<LightDesc>& lights;  // the frame's lights, in the order of lightBuffer
  GLuint lightBuffer = 0;  // their GpuLight SSBO (the light paths pack `lights` for Vulkan)
  ShadowTracing tracing = ShadowTracing::Auto;
  const std::vector<Material>& materials;  // the frame's (MaterialTable), one per scene material
};

// How the slots were filled.
struct VplLayout {
  int count = 0;         // slots: vpl_count
  int paths = 0;         // P
  int slotsPerPath = 0;  // S
  bool emissionSlot = false;
};

class VplTracer {
 public:
  VplTracer() = default;
  VplTracer(const VplTracer&) = delete;
  VplTracer& operator=(const VplTracer&) = delete;

  // Fills `vpls` (reserved for N PointLights here) with this frame's VPLs. Throws lgh::Error:
  // Unavailable (naming /settings/gi/enabled) when the machine cannot trace rays, Internal for a
  // Vulkan failure.
  VplLayout generate(const VplTracingInputs& inputs, const CachedScene& scene, GiTracing& tracing,
                     gl::SizedBuffer& vpls, gl::GpuTimer& timer, FrameReport& report);

  // Adds the writer of the last generate()'s rows that come after the GL timer to
  // report.lateRows (read when the frame is taken): "gi as build", "gi vpls" (the Vulkan
  // submission's span; TimingTable::appendMerged keeps GL's span around the hand-over where that
  // is longer) with the Vulkan steps inside it ("gi emit", "gi bounce <b>", "gi rays"), "gi
  // transfer" (CPU).
  void collectTimings(const GiTracing& tracing, FrameReport& report);

 private:
  void clearSlots(GLuint vpls, int from, int count);

  std::vector<GpuLight> lights_;
  double transferMs_ = 0.0;
  std::function<double()> asBuildGpuMs_;
  int bounces_ = 0;
  bool traced_ = false;
};

// Work groups of 64 for `items` invocations, 2D beyond 65535 groups (gi_*.comp find their
// index as (group.y * groups.x + group.x) * 64 + local.x).
void dispatchGi(std::uint32_t items);

}  // namespace lgh
