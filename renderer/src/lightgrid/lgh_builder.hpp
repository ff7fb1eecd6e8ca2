// Builds the Lighting Grid Hierarchy on the GPU from a buffer of point lights (Lin & Yuksel 2019,
// Sec. 3.1): bounds -> [auto levels] -> S1 by scatter (direct, or binned by tile and summed in
// shared memory) -> S2..SL by gather from S1 (or every level by scatter) -> stream compaction
// straight into one merged grid-light buffer, plus the level table and indirect draw commands.
// Everything after the call to build() stays on the GPU: sizes the CPU cannot know are turned into
// glDispatchComputeIndirect arguments by the kernels themselves. docs/LGH.md describes the steps,
// buffer layouts and tolerances.
//
// Needs a current GL 4.5 context on the calling thread for its whole life.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"
#include "gl/gpu_timer.hpp"
#include "lightgrid/lgh_types.hpp"

namespace lgh {

class LghBuilder {
 public:
  // Compiles the kernels of the default atomics path (the other path compiles on first use).
  LghBuilder();
  ~LghBuilder();
  LghBuilder(const LghBuilder&) = delete;
  LghBuilder& operator=(const LghBuilder&) = delete;

  // Builds from `count` PointLights in `lightsBuffer` (a GL buffer name; read as an SSBO). Records
  // one GPU timer pass per step when `timer` is given. Never waits for the GPU. Invalid lights
  // (non-finite or out-of-range values) make the hierarchy empty on the GPU; validate() or
  // readLevels() tell. Throws lgh::Error(Invalid) for a negative count, Unavailable when
  // settings.atomics is Float without GL_NV_shader_atomic_float.
  void build(GLuint lightsBuffer, int count, const LghBuildSettings& settings,
             gl::GpuTimer* timer = nullptr);

  // Checks the lights on the GPU and waits for the answer: throws lgh::Error(Invalid) naming how
  // many lights have a NaN/inf/out-of-range position or intensity. Separate from build() because
  // it stalls.
  void validate(GLuint lightsBuffer, int count);

  // Reads the level table of the last build back to the CPU (waits for the GPU).
  LghLevelTable readLevels() const;
  // Reads every grid light of the last build (waits for the GPU). For tests and reports.
  std::vector<GridLight> readGridLights() const;
  std::vector<DrawArraysIndirectCommand> readDrawCommands() const;

  // Output buffers, owned by the builder and valid until the next build() reallocates them.
  GLuint gridLights() const { return gridLights_.id(); }  // GridLight[]
  GLuint levels() const { return levels_.id(); }          // LghLevelTable
  GLuint drawCommands() const { return draws_.id(); }     // DrawArraysIndirectCommand[18]

  bool floatAtomicsAvailable() const { return floatAtomicsAvailable_; }
  // The dense vertex budget a build of `count` lights with `settings` gets: lghResolveDenseBudget
  // capped by what one SSBO binding may hold on this device (GL_MAX_SHADER_STORAGE_BLOCK_SIZE).
  std::size_t denseBudget(int count, const LghBuildSettings& settings) const;
  // Bytes of GPU memory the builder holds.
  std::size_t allocatedBytes() const;

 private:
  struct CommonPrograms;
  struct AccumPrograms;
  struct Programs {
    const CommonPrograms& common;
    const AccumPrograms& accum;
  };
  struct Capacity {
    std::size_t lights = 0;
    std::size_t denseVertices = 0;
    std::size_t gridLights = 0;
    std::size_t s1Lights = 0;
    bool fixedPoint = false;
    // Binned S1 only (0 otherwise): tiles the S1 grid may have, (tile, chunk) work items.
    std::size_t binTiles = 0;
    std::size_t binItems = 0;
  };

  Programs programs(bool fixedPoint);
  bool useFixedPoint(LghAtomics atomics) const;
  Capacity capacityFor(int count, const LghBuildSettings& settings, bool fixedPoint) const;
  void reserve(const Capacity& needed);
  void bindBuffers(GLuint lightsBuffer) const;
  void runBounds(const Programs& p, int count, const LghBuildSettings& settings, bool fixedPoint);
  void runAutoLevels(const Programs& p, int count);
  void runS1(const Programs& p, int count, const LghBuildSettings& settings);
  void runBinnedS1(const Programs& p, int count, GLuint clearWords);
  void runCompaction(const Programs& p, int slot, int firstLevel, bool onlyFirst, bool final,
                     const LghBuildSettings& settings);
  void runGather(const Programs& p, const LghBuildSettings& settings, gl::GpuTimer* timer);
  void runScatterLevels(const Programs& p, const LghBuildSettings& settings, gl::GpuTimer* timer);
  void dispatchSlot(int slot) const;
  void readBack(GLuint source, GLsizeiptr bytes, void* out) const;

  bool floatAtomicsAvailable_ = false;
  GLint64 maxBlockBytes_ = 0;
  std::unique_ptr<CommonPrograms> common_;
  std::unique_ptr<AccumPrograms> accumPrograms_[2];  // [fixedPoint]
  Capacity capacity_;

  gl::SizedBuffer levels_;
  gl::SizedBuffer state_;
  gl::SizedBuffer partials_;
  gl::SizedBuffer accum_;
  gl::SizedBuffer gridLights_;
  gl::SizedBuffer records_;
  gl::SizedBuffer rank_;
  gl::SizedBuffer bitmaps_;
  gl::SizedBuffer blocks_;
  gl::SizedBuffer draws_;
  gl::SizedBuffer touched_;
  gl::SizedBuffer binCount_;         // binned S1: lights per tile (zero between builds)
  gl::SizedBuffer binStart_;         // tile offsets into the sorted lights (kept in records_)
  gl::SizedBuffer binItems_;         // (tile, chunk) work items
  mutable gl::SizedBuffer staging_;  // client-side copy target of the read-backs
};

}  // namespace lgh
