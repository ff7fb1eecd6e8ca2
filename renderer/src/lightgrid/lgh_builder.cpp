#include "lightgrid/lgh_builder.hpp"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "lgh/error.hpp"

namespace lgh {
namespace {

// The sizes and slots the kernels use, from glsl/include/slots.glsl.
constexpr GLuint kGroup = LGH_GROUP;
constexpr GLuint kBoundsItems = LGH_BOUNDS_ITEMS;
constexpr std::size_t kBlock = LGH_BLOCK;
constexpr int kPyramidSteps = LGH_PYRAMID_STEPS;
constexpr int kSlotPyramid = LGH_SLOT_PYRAMID;
constexpr int kSlotCompactS1 = LGH_SLOT_COMPACT_S1;
constexpr int kSlotCompactRest = LGH_SLOT_COMPACT_REST;
constexpr int kSlotCompactAll = LGH_SLOT_COMPACT_ALL;
constexpr int kSlotGatherAll = LGH_SLOT_GATHER_ALL;
constexpr int kSlotGather = LGH_SLOT_GATHER;    // + level
constexpr int kSlotScatter = LGH_SLOT_SCATTER;  // + level
constexpr int kSlotBinAccum = LGH_SLOT_BIN_ACCUM;
constexpr GLsizeiptr kStateBytes = 2048;                   // LghState is 1760 bytes
constexpr std::size_t kBinTileFloat = LGH_BIN_TILE_FLOAT;  // S1 cells per tile edge
constexpr std::size_t kBinTileFixed = LGH_BIN_TILE_FIXED;
constexpr std::size_t kBinChunk = LGH_BIN_CHUNK;  // lights per accumulation work group

enum Binding : GLuint {
  kLights = LGH_BIND_BUILD_LIGHTS,
  kLevels = LGH_BIND_BUILD_LEVELS,
  kState = LGH_BIND_BUILD_STATE,
  kPartials = LGH_BIND_BUILD_PARTIALS,
  kAccum = LGH_BIND_BUILD_ACCUM,
  kGridLights = LGH_BIND_BUILD_GRID_LIGHTS,
  kRecords = LGH_BIND_BUILD_RECORDS,
  kRank = LGH_BIND_BUILD_RANK,
  kBitmaps = LGH_BIND_BUILD_BITMAPS,
  kBlocks = LGH_BIND_BUILD_BLOCKS,
  kDraws = LGH_BIND_BUILD_DRAWS,
  kTouched = LGH_BIND_BUILD_TOUCHED,
  kBinCount = LGH_BIND_BUILD_BIN_COUNT,
  kBinStart = LGH_BIND_BUILD_BIN_START,
  kBinItems = LGH_BIND_BUILD_BIN_ITEMS,
};

struct BoundsPartial {
  glm::vec4 minMaxC;
  glm::vec4 maxPad;
  glm::uvec4 counts;
};
static_assert(sizeof(BoundsPartial) == 48);
constexpr std::size_t kRecordBytes = 48;
constexpr std::size_t kBinLightBytes = 32;  // LghBinLight, kept in the records' buffer

GLuint ceilDiv(std::size_t a, std::size_t b) { return static_cast<GLuint>((a + b - 1) / b); }

// Work groups as the kernels linearize them (lghGroupIndex): 2D past 65535.
void dispatch2D(GLuint groups) {
  if (groups == 0) return;
  const GLuint x = std::min<GLuint>(groups, 65535);
  glDispatchCompute(x, ceilDiv(groups, 65535), 1);
}

void setUniform(GLuint program, const char* name, GLuint value) {
  const GLint location = glGetUniformLocation(program, name);
  if (location >= 0) glProgramUniform1ui(program, location, value);
}

void storageBarrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); }

class OptionalPass {
 public:
  OptionalPass(gl::GpuTimer* timer, const std::string& name) {
    if (timer != nullptr) pass_.emplace(*timer, name);
  }

 private:
  std::optional<gl::ScopedGpuPass> pass_;
};

}  // namespace

struct LghBuilder::CommonPrograms {
  gl::Program bounds = gl::buildComputeProgram("lgh_bounds.comp");
  gl::Program boundsOnly = gl::buildComputeProgram("lgh_bounds.comp", "#define LGH_BOUNDS_ONLY 1");
  gl::Program mark = gl::buildComputeProgram("lgh_occupancy.comp");
  gl::Program step = gl::buildComputeProgram("lgh_occupancy.comp", "#define LGH_OCC_STEP 1");
  gl::Program binCount = gl::buildComputeProgram("lgh_bin_count.comp");
  gl::Program binScatter = gl::buildComputeProgram("lgh_bin_scatter.comp");
};

// The kernels that touch the accumulators, compiled once per atomics mode.
struct LghBuilder::AccumPrograms {
  explicit AccumPrograms(const std::string& defines)
      : scatter(gl::buildComputeProgram("lgh_scatter.comp", defines)),
        gather(gl::buildComputeProgram("lgh_gather.comp", defines)),
        count(gl::buildComputeProgram("lgh_compact_count.comp", defines)),
        write(gl::buildComputeProgram("lgh_compact_write.comp", defines)),
        binAccum(gl::buildComputeProgram("lgh_bin_accum.comp", defines)) {}
  gl::Program scatter;
  gl::Program gather;
  gl::Program count;
  gl::Program write;
  gl::Program binAccum;
};

// GPU-only storage: no DYNAMIC_STORAGE / MAP bits, so drivers keep it in video memory (reads go
// through staging_).
constexpr GLbitfield kGpuOnly = 0;

LghBuilder::LghBuilder()
    : floatAtomicsAvailable_(gl::api("extension flags").NV_shader_atomic_float != 0) {
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlockBytes_);
  levels_.reserve(sizeof(LghLevelTableGpu), kGpuOnly);
  draws_.reserve(kLghDrawCommands * sizeof(DrawArraysIndirectCommand), kGpuOnly);
  state_.reserve(kStateBytes, kGpuOnly);
  for (const gl::SizedBuffer* buffer : {&levels_, &draws_, &state_}) {
    glClearNamedBufferData(buffer->id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  }
  programs(!floatAtomicsAvailable_);  // compile now, not inside the first timed build
}

LghBuilder::~LghBuilder() = default;

bool LghBuilder::useFixedPoint(LghAtomics atomics) const {
  if (atomics == LghAtomics::Float && !floatAtomicsAvailable_) {
    throw Error(ErrorCode::Unavailable,
                "LGH float atomics asked for, but GL_NV_shader_atomic_float is missing");
  }
  return atomics == LghAtomics::FixedPoint || !floatAtomicsAvailable_;
}

LghBuilder::Programs LghBuilder::programs(bool fixedPoint) {
  if (!common_) common_ = std::make_unique<CommonPrograms>();
  auto& accum = accumPrograms_[fixedPoint ? 1 : 0];
  if (!accum) {
    accum = std::make_unique<AccumPrograms>(
        fixedPoint
            ? std::string()
            : "#extension GL_NV_shader_atomic_float : require\n#define LGH_FLOAT_ATOMICS 1\n");
  }
  return Programs{*common_, *accum};
}

std::size_t LghBuilder::denseBudget(int count, const LghBuildSettings& settings) const {
  return capacityFor(std::max(count, 0), settings, useFixedPoint(settings.atomics)).denseVertices;
}

LghBuilder::Capacity LghBuilder::capacityFor(int count, const LghBuildSettings& settings,
                                             bool fixedPoint) const {
  const auto n = static_cast<std::size_t>(count);
  const auto maxBytes = static_cast<std::size_t>(std::max<GLint64>(maxBlockBytes_, 1 << 24));
  const std::size_t stride = fixedPoint ? 72 : 36;
  const std::size_t budget =
      lghResolveDenseBudget(n, settings, std::min(maxBytes / stride, maxBytes / sizeof(GridLight)));
  Capacity capacity;
  capacity.lights = n;
  capacity.denseVertices = budget;
  capacity.gridLights = std::max<std::size_t>(1, std::min(budget, 8 * n * kLghMaxLevels));
  capacity.s1Lights = std::max<std::size_t>(1, std::min(budget, 8 * n));
  capacity.fixedPoint = fixedPoint;
  if (lghUseBinnedS1(settings, count)) {
    // Per axis max(1, ceil(c / T)) tiles for c cells: at most 2 (c + 1) / T when c >= T, 1 when
    // c < T; so over the three axes at most max(1, 2 n / T) for n S1 vertices, n <= budget.
    const std::size_t tile = fixedPoint ? kBinTileFixed : kBinTileFloat;
    capacity.binTiles = 2 * budget / tile + 1;
    // Occupied tiles (at most one per light) plus one item per further chunk.
    capacity.binItems = std::min(capacity.binTiles, n) + n / kBinChunk + 1;
  }
  return capacity;
}

void LghBuilder::reserve(const Capacity& needed) {
  const std::size_t stride = needed.fixedPoint ? 72 : 36;
  // A build leaves the accumulators and touched bits zeroed (the compaction clears what it
  // consumed); a new buffer starts that way once.
  auto reserveZeroed = [](gl::SizedBuffer& buffer, std::size_t bytes) {
    const GLuint before = buffer.id();
    buffer.reserve(static_cast<GLsizeiptr>(bytes), kGpuOnly);
    if (buffer.id() != before) {
      glClearNamedBufferData(buffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    }
  };
  reserveZeroed(accum_, needed.denseVertices * stride);
  reserveZeroed(touched_, (needed.denseVertices / 32 + 1) * sizeof(GLuint));
  const std::size_t partials =
      std::max<std::size_t>(1, ceilDiv(needed.lights, std::size_t{kGroup} * kBoundsItems));
  auto reserve = [](gl::SizedBuffer& buffer, std::size_t bytes) {
    buffer.reserve(static_cast<GLsizeiptr>(bytes), kGpuOnly);
  };
  reserve(partials_, partials * sizeof(BoundsPartial));
  reserve(gridLights_, needed.gridLights * sizeof(GridLight));
  // The binned S1 keeps its sorted lights in the records' buffer (records are written later).
  reserve(records_, std::max(needed.s1Lights * kRecordBytes,
                             needed.binTiles > 0 ? needed.lights * kBinLightBytes : 0));
  reserve(rank_, (needed.denseVertices + 1) * sizeof(GLuint));
  // Cleared by the S1 scatter after each use.
  reserveZeroed(bitmaps_, (needed.denseVertices / 32 + kLghMaxLevels) * sizeof(GLuint));
  reserve(blocks_, (needed.denseVertices / kBlock + kLghMaxLevels) * sizeof(GLuint));
  // Bound even when unused: at least a word each.
  reserveZeroed(binCount_, std::max<std::size_t>(needed.binTiles, 1) * sizeof(GLuint));
  reserve(binStart_, (needed.binTiles + 1) * sizeof(GLuint));
  reserve(binItems_, std::max<std::size_t>(needed.binItems, 1) * 2 * sizeof(GLuint));
}

std::size_t LghBuilder::allocatedBytes() const {
  std::size_t total = 0;
  for (const gl::SizedBuffer* buffer :
       {&levels_, &state_, &partials_, &accum_, &gridLights_, &records_, &rank_, &bitmaps_,
        &blocks_, &draws_, &touched_, &binCount_, &binStart_, &binItems_}) {
    total += static_cast<std::size_t>(buffer->size);
  }
  return total;
}

void LghBuilder::bindBuffers(GLuint lightsBuffer) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLights, lightsBuffer);
  const std::pair<Binding, const gl::SizedBuffer*> buffers[] = {
      {kLevels, &levels_},     {kState, &state_},           {kPartials, &partials_},
      {kAccum, &accum_},       {kGridLights, &gridLights_}, {kRecords, &records_},
      {kRank, &rank_},         {kBitmaps, &bitmaps_},       {kBlocks, &blocks_},
      {kDraws, &draws_},       {kTouched, &touched_},       {kBinCount, &binCount_},
      {kBinStart, &binStart_}, {kBinItems, &binItems_}};
  for (const auto& [binding, buffer] : buffers) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer->id());
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, state_.id());
}

void LghBuilder::dispatchSlot(int slot) const {
  glDispatchComputeIndirect(static_cast<GLintptr>(slot) * 16);
}

void LghBuilder::build(GLuint lightsBuffer, int count, const LghBuildSettings& settings,
                       gl::GpuTimer* timer) {
  if (count < 0) throw Error(ErrorCode::Invalid, fmt::format("negative light count {}", count));
  const bool fixedPoint = useFixedPoint(settings.atomics);
  const Programs p = programs(fixedPoint);
  const Capacity needed = capacityFor(count, settings, fixedPoint);
  reserve(needed);
  capacity_ = needed;
  bindBuffers(lightsBuffer);
  {
    OptionalPass pass(timer, "lgh bounds");
    runBounds(p, count, settings, fixedPoint);
  }
  if (settings.levels <= 0) {
    OptionalPass pass(timer, "lgh auto levels");
    runAutoLevels(p, count);
  }
  {
    OptionalPass pass(timer, "lgh S1");
    runS1(p, count, settings);
  }
  if (settings.method == LghSettings::Method::Gather) {
    {
      OptionalPass pass(timer, "lgh S1 compact");
      runCompaction(p, kSlotCompactS1, 1, true, false, settings);
    }
    runGather(p, settings, timer);
    OptionalPass pass(timer, "lgh merge");
    runCompaction(p, kSlotCompactRest, 2, false, true, settings);
  } else {
    runScatterLevels(p, settings, timer);
    OptionalPass pass(timer, "lgh merge");
    runCompaction(p, kSlotCompactAll, 1, false, true, settings);
  }
  glUseProgram(0);
  // Consumers: SSBO reads, indirect draws, and read-backs or clears of these buffers.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT);
}

// One dispatch: the bounds partials, then (last work group) the set-up of the whole build.
void LghBuilder::runBounds(const Programs& p, int count, const LghBuildSettings& settings,
                           bool fixedPoint) {
  const GLuint groups =
      ceilDiv(static_cast<std::size_t>(count), std::size_t{kGroup} * kBoundsItems);
  GLuint flags = settings.levels <= 0 ? kLghFlagAutoLevels : 0;
  if (fixedPoint) flags |= kLghFlagFixedPoint;
  if (settings.method == LghSettings::Method::Gather) flags |= kLghFlagGather;
  const GLuint bounds = p.common.bounds.id();
  glUseProgram(bounds);
  setUniform(bounds, "u_count", static_cast<GLuint>(count));
  setUniform(bounds, "u_groups", groups);
  setUniform(bounds, "u_requestedLevels",
             static_cast<GLuint>(std::clamp(settings.levels, 0, kLghMaxLevels)));
  setUniform(bounds, "u_budget", static_cast<GLuint>(capacity_.denseVertices));
  setUniform(bounds, "u_flags", flags);
  setUniform(bounds, "u_levelLimit", kLghMaxLevels);
  dispatch2D(std::max<GLuint>(groups, 1));  // the set-up runs even without lights
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

// The finest candidate's occupancy, then up to 3 pyramid steps (empty when not needed); the last
// work group of the last needed one builds the small candidates and chooses L.
void LghBuilder::runAutoLevels(const Programs& p, int count) {
  const GLuint mark = p.common.mark.id();
  glUseProgram(mark);
  setUniform(mark, "u_count", static_cast<GLuint>(count));
  setUniform(mark, "u_levelLimit", kLghMaxLevels);
  dispatch2D(std::max<GLuint>(ceilDiv(static_cast<std::size_t>(count), kGroup), 1));
  storageBarrier();
  const GLuint step = p.common.step.id();
  glUseProgram(step);
  setUniform(step, "u_levelLimit", kLghMaxLevels);
  for (int s = 0; s < kPyramidSteps; ++s) {
    setUniform(step, "u_step", static_cast<GLuint>(s));
    dispatchSlot(kSlotPyramid + s);
    storageBarrier();
  }
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
}

// S1 from the input lights; either way it also clears the auto levels' occupancy bitmaps.
void LghBuilder::runS1(const Programs& p, int count, const LghBuildSettings& settings) {
  const auto bitmapWords = static_cast<GLuint>(bitmaps_.size / sizeof(GLuint));
  const GLuint clearWords = settings.levels <= 0 ? bitmapWords : 0;
  if (lghUseBinnedS1(settings, count)) {
    runBinnedS1(p, count, clearWords);
    return;
  }
  glUseProgram(p.accum.scatter.id());
  setUniform(p.accum.scatter.id(), "u_level", 1);
  setUniform(p.accum.scatter.id(), "u_clearWords", clearWords);
  dispatchSlot(kSlotScatter + 1);
  storageBarrier();
}

// Count per tile (+ offsets and work items in its last work group) -> sort the lights by tile ->
// one work group per (tile, chunk) sums in shared memory and flushes to the accumulators.
void LghBuilder::runBinnedS1(const Programs& p, int count, GLuint clearWords) {
  const GLuint binCount = p.common.binCount.id();
  glUseProgram(binCount);
  setUniform(binCount, "u_clearWords", clearWords);
  dispatch2D(std::max<GLuint>(ceilDiv(static_cast<std::size_t>(count), kGroup), 1));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  glUseProgram(p.common.binScatter.id());
  dispatchSlot(kSlotScatter + 1);  // one thread per light; no groups without levels
  storageBarrier();
  glUseProgram(p.accum.binAccum.id());
  dispatchSlot(kSlotBinAccum);
  storageBarrier();
}

// Count (+ offsets in its last work group) -> write, over the blocks of levels
// firstLevel..(onlyFirst ? firstLevel : L).
void LghBuilder::runCompaction(const Programs& p, int slot, int firstLevel, bool onlyFirst,
                               bool final, const LghBuildSettings& settings) {
  const bool writeS1 = onlyFirst && firstLevel == 1;
  const auto capacity = static_cast<GLuint>(
      writeS1 ? std::min(capacity_.gridLights, capacity_.s1Lights) : capacity_.gridLights);
  const GLuint count = p.accum.count.id();
  glUseProgram(count);
  setUniform(count, "u_slot", static_cast<GLuint>(slot));
  setUniform(count, "u_firstLevel", static_cast<GLuint>(firstLevel));
  setUniform(count, "u_onlyFirst", onlyFirst ? 1 : 0);
  setUniform(count, "u_final", final ? 1 : 0);
  setUniform(count, "u_capacity", capacity);
  setUniform(count, "u_startLevel", static_cast<GLuint>(std::max(settings.drawStartLevel, 1)));
  setUniform(count, "u_vertexCount", static_cast<GLuint>(std::max(settings.cubeVertexCount, 0)));
  dispatchSlot(slot);
  storageBarrier();
  const GLuint write = p.accum.write.id();
  glUseProgram(write);
  setUniform(write, "u_slot", static_cast<GLuint>(slot));
  setUniform(write, "u_firstLevel", static_cast<GLuint>(firstLevel));
  setUniform(write, "u_writeS1", writeS1 ? 1 : 0);
  setUniform(write, "u_capacity", capacity);
  dispatchSlot(slot);
  storageBarrier();
}

// Levels the CPU must issue dispatches for: the explicit count, or every possible level when the
// GPU picks it (dispatches past the chosen L have zero work groups).
static int dispatchedLevels(const LghBuildSettings& settings) {
  return settings.levels > 0 ? std::min(settings.levels, kLghMaxLevels) : kLghMaxLevels;
}

void LghBuilder::runGather(const Programs& p, const LghBuildSettings& settings,
                           gl::GpuTimer* timer) {
  const GLuint gather = p.accum.gather.id();
  glUseProgram(gather);
  if (!settings.splitLevels) {
    OptionalPass pass(timer, "lgh S2+");
    setUniform(gather, "u_level", 0);
    dispatchSlot(kSlotGatherAll);
    storageBarrier();
    return;
  }
  for (int level = 2; level <= dispatchedLevels(settings); ++level) {
    OptionalPass pass(timer, fmt::format("lgh S{}", level));
    setUniform(gather, "u_level", static_cast<GLuint>(level));
    dispatchSlot(kSlotGather + level);
    storageBarrier();
  }
}

void LghBuilder::runScatterLevels(const Programs& p, const LghBuildSettings& settings,
                                  gl::GpuTimer* timer) {
  const GLuint scatter = p.accum.scatter.id();
  glUseProgram(scatter);
  setUniform(scatter, "u_clearWords", 0);
  for (int level = 2; level <= dispatchedLevels(settings); ++level) {
    OptionalPass pass(timer, fmt::format("lgh S{}", level));
    setUniform(scatter, "u_level", static_cast<GLuint>(level));
    dispatchSlot(kSlotScatter + level);
    storageBarrier();
  }
}

void LghBuilder::validate(GLuint lightsBuffer, int count) {
  if (count < 0) throw Error(ErrorCode::Invalid, fmt::format("negative light count {}", count));
  if (count == 0) return;
  const Programs p = programs(!floatAtomicsAvailable_);
  const GLuint groups =
      ceilDiv(static_cast<std::size_t>(count), std::size_t{kGroup} * kBoundsItems);
  partials_.reserve(static_cast<GLsizeiptr>(groups * sizeof(BoundsPartial)), kGpuOnly);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLights, lightsBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPartials, partials_.id());
  const GLuint bounds = p.common.boundsOnly.id();
  glUseProgram(bounds);
  setUniform(bounds, "u_count", static_cast<GLuint>(count));
  setUniform(bounds, "u_groups", groups);
  dispatch2D(groups);
  glUseProgram(0);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<BoundsPartial> partials(groups);
  readBack(partials_.id(), static_cast<GLsizeiptr>(partials.size() * sizeof(BoundsPartial)),
           partials.data());
  std::uint64_t invalid = 0;
  for (const BoundsPartial& partial : partials) invalid += partial.counts.y;
  if (invalid > 0) {
    throw Error(ErrorCode::Invalid,
                fmt::format("{} of {} point lights have a NaN, infinite or out-of-range position "
                            "or intensity (|x| <= 1e30, 0 <= intensity <= 1e30)",
                            invalid, count),
                "lights");
  }
}

// Through a client-storage staging buffer: reading a video-memory buffer directly made the
// NVIDIA driver migrate it to host memory ("performance warning"), slowing every later build.
void LghBuilder::readBack(GLuint source, GLsizeiptr bytes, void* out) const {
  if (bytes <= 0) return;
  staging_.reserve(bytes, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
  glCopyNamedBufferSubData(source, staging_.id(), 0, 0, bytes);
  glGetNamedBufferSubData(staging_.id(), 0, bytes, out);
}

LghLevelTable LghBuilder::readLevels() const {
  LghLevelTableGpu gpu;
  readBack(levels_.id(), sizeof(gpu), &gpu);
  return LghLevelTable::fromGpu(gpu);
}

std::vector<GridLight> LghBuilder::readGridLights() const {
  const LghLevelTable table = readLevels();
  std::vector<GridLight> lights(table.totalLights);
  readBack(gridLights_.id(), static_cast<GLsizeiptr>(lights.size() * sizeof(GridLight)),
           lights.data());
  return lights;
}

std::vector<DrawArraysIndirectCommand> LghBuilder::readDrawCommands() const {
  std::vector<DrawArraysIndirectCommand> commands(kLghDrawCommands);
  readBack(draws_.id(), static_cast<GLsizeiptr>(commands.size() * sizeof(commands[0])),
           commands.data());
  return commands;
}

}  // namespace lgh
