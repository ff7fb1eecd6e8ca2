// Upload staging (RendererOptions::uploadStagingBytes, docs/ARCHITECTURE.md "Upload staging"):
// prefetch threads copy parsed scenes into persistently mapped memory, and the render thread
// uploads them as GPU copies. On whichever context path the suite runs:
//  - the staging memory hands out aligned spans, merges those given back, refuses what does not
//    fit, and frees a retired span once the GPU is past the commands that read it;
//  - a GPU copy reads what another thread wrote into the mapped memory;
//  - thumbnails of real assets uploaded from staging memory have the pixels of the same frames
//    uploaded from the scenes' own memory, say so in the decision `scene_upload`, and give every
//    staged byte back; a scene larger than the staging memory is uploaded from its own memory.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_helpers.hpp"
#include "gl/gl_objects.hpp"
#include "gl/staging_memory.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;
using lgh::gl::StagingMemory;
using lgh::test::pixelBytes;
using lgh::test::renderHintedFirst;
using lgh::test::thumbnailRequest;
constexpr std::size_t kAlign = StagingMemory::kAlignment;

TEST(StagingMemory, SpansAreAlignedMergedWhenGivenBackAndRefusedWhenTheyDoNotFit) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  StagingMemory memory(16 * kAlign);
  EXPECT_EQ(memory.capacity(), 16 * kAlign);
  auto first = memory.reserve(3 * kAlign - 10);
  auto second = memory.reserve(1);
  auto third = memory.reserve(12 * kAlign);
  ASSERT_TRUE(first && second && third);
  EXPECT_EQ(first->size(), 3 * kAlign);
  EXPECT_EQ(second->size(), kAlign);
  for (const auto* region : {&*first, &*second, &*third}) {
    EXPECT_EQ(region->offset() % static_cast<GLintptr>(kAlign), 0);
  }
  EXPECT_EQ(memory.bytesInUse(), 16 * kAlign);
  EXPECT_FALSE(memory.reserve(1)) << "full";
  // The first two spans given back make one span of four.
  first->reset();
  second->reset();
  EXPECT_EQ(memory.bytesInUse(), 12 * kAlign);
  auto merged = memory.reserve(4 * kAlign);
  ASSERT_TRUE(merged);
  EXPECT_EQ(merged->offset(), 0);
  merged->reset();
  third->reset();
  EXPECT_EQ(memory.bytesInUse(), 0U);
  EXPECT_TRUE(memory.reserve(16 * kAlign)) << "everything merged back into one span";
  EXPECT_FALSE(memory.reserve(17 * kAlign)) << "larger than the memory";
}

TEST(StagingMemory, ARetiredSpanIsFreeOnceTheGpuIsPastItsCommands) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  StagingMemory memory(4 * kAlign);
  auto region = memory.reserve(4 * kAlign);
  ASSERT_TRUE(region);
  memory.retire(std::move(*region));
  EXPECT_EQ(memory.bytesInUse(), 4 * kAlign) << "retired, not yet reclaimed";
  EXPECT_FALSE(memory.reserve(kAlign));
  glFinish();
  memory.reclaim();
  EXPECT_EQ(memory.bytesInUse(), 0U);
  EXPECT_TRUE(memory.reserve(4 * kAlign));
}

TEST(StagingMemory, AGpuCopyReadsWhatAnotherThreadWrote) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  StagingMemory memory(1 << 20);
  std::vector<std::uint32_t> values(50'000);
  std::iota(values.begin(), values.end(), 0xabc00000U);
  const std::size_t bytes = values.size() * sizeof(std::uint32_t);
  std::optional<StagingMemory::Region> region;
  std::thread writer([&] {
    region = memory.reserve(bytes);
    if (region) std::memcpy(region->data(), values.data(), bytes);
  });
  writer.join();
  ASSERT_TRUE(region);
  lgh::gl::Buffer target;
  glNamedBufferStorage(target.id(), static_cast<GLsizeiptr>(bytes), nullptr, 0);
  glCopyNamedBufferSubData(memory.buffer(), target.id(), region->offset(), 0,
                           static_cast<GLsizeiptr>(bytes));
  memory.retire(std::move(*region));
  std::vector<std::uint32_t> read(values.size(), 0);
  glGetNamedBufferSubData(target.id(), 0, static_cast<GLsizeiptr>(bytes), read.data());
  EXPECT_EQ(read, values);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

lgh::RendererOptions options(std::int64_t stagingBytes) {
  lgh::RendererOptions opts = lgh::test::rendererOptions();
  opts.assetRoot = lgh::test::assimpGltfDir();
  opts.uploadStagingBytes = stagingBytes;
  opts.uploadStagingMinBytes = 0;  // every scene parsed ahead, however small
  opts.sceneCacheBytes = 0;        // every new scene evicts the one before
  return opts;
}

// Textured (colour and data uses of one image), untextured, many primitives (2CylinderEngine:
// 4.9 MB of vertices and indices), lines and points, and one repeated after others.
const std::vector<std::string>& assets() {
  static const std::vector<std::string> list = {
      "BoxTextured-glTF/BoxTextured.gltf",
      "BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
      "ClearCoat-glTF/ClearCoatTest.gltf",
      "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
      "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf",
      "BoxTextured-glTF/BoxTextured.gltf"};
  return list;
}

std::string uploadOf(const lgh::RenderResult& result) {
  const auto found = result.decisions.find("scene_upload");
  return found == result.decisions.end() ? "(none)" : found->second;
}

TEST(UploadStaging, StagedScenesDrawAsScenesUploadedFromTheirOwnMemory) {
  std::vector<json> frames;
  for (const std::string& asset : assets()) {
    frames.push_back(thumbnailRequest(asset, true));
    frames.push_back(thumbnailRequest(asset, false));  // the same scene, drawn again at once
  }
  lgh::Renderer staging(options(64LL << 20));
  lgh::Renderer plain(options(0));
  EXPECT_EQ(staging.sceneCacheStats().stagingBytes, std::size_t{64} << 20);
  EXPECT_EQ(plain.sceneCacheStats().stagingBytes, 0U);
  const auto staged = renderHintedFirst(staging, frames);
  const auto own = renderHintedFirst(plain, frames);
  ASSERT_EQ(staged.size(), frames.size());
  ASSERT_EQ(own.size(), frames.size());
  int stagedUploads = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + frames[i].dump());
    EXPECT_EQ(pixelBytes(staged[i]), pixelBytes(own[i]));
    EXPECT_EQ(own[i].decisions.count("scene_upload"), 0U) << "no staging, no decision";
    const std::string upload = uploadOf(staged[i]);
    if (i % 2 == 1) {
      EXPECT_EQ(upload, "cached") << "the second view of a scene draws the cached upload";
      continue;
    }
    // A scene parsed ahead is staged; one whose hint found no room in the look-ahead (parses in
    // process) is parsed and uploaded when drawn.
    const bool prefetched = staged[i].decisions.count("scene_parse") == 1;
    EXPECT_EQ(upload, prefetched ? "staged" : "render_thread");
    stagedUploads += upload == "staged" ? 1 : 0;
  }
  EXPECT_GE(stagedUploads, 3);
  // The last frame's upload may still be retired: the next lookup reclaims it.
  renderHintedFirst(staging, {thumbnailRequest(assets().front(), false)});
  const auto stats = staging.sceneCacheStats();
  EXPECT_LE(stats.stagingBytesInUse, stats.stagingBytes);
  renderHintedFirst(staging, {thumbnailRequest(assets().back(), false)});
  EXPECT_EQ(staging.sceneCacheStats().stagingBytesInUse, 0U)
      << "every staged byte given back once its copies were done";
}

TEST(UploadStaging, ASceneLargerThanTheStagingMemoryIsUploadedFromItsOwnMemory) {
  const std::vector<json> frames = {
      thumbnailRequest("BoxTextured-glTF/BoxTextured.gltf", false),
      thumbnailRequest("2CylinderEngine-glTF-Binary/2CylinderEngine.glb", false)};
  lgh::Renderer small(options(1LL << 20));  // 2CylinderEngine needs 4.9 MB
  lgh::Renderer plain(options(0));
  const auto results = renderHintedFirst(small, frames);
  const auto own = renderHintedFirst(plain, frames);
  ASSERT_EQ(results.size(), 2U);
  ASSERT_EQ(own.size(), 2U);
  EXPECT_EQ(uploadOf(results[0]), "staged");
  EXPECT_EQ(uploadOf(results[1]), "render_thread");
  for (std::size_t i = 0; i < results.size(); ++i) {
    EXPECT_EQ(pixelBytes(results[i]), pixelBytes(own[i])) << frames[i].dump();
  }
}

TEST(UploadStaging, ScenesBelowTheThresholdAreUploadedFromTheirOwnMemory) {
  const std::vector<json> frames = {
      thumbnailRequest("BoxTextured-glTF/BoxTextured.gltf", false),
      thumbnailRequest("2CylinderEngine-glTF-Binary/2CylinderEngine.glb", false)};
  lgh::RendererOptions opts = options(64LL << 20);
  opts.uploadStagingMinBytes = std::size_t{1} << 20;  // the default: BoxTextured is 0.3 MB
  EXPECT_EQ(opts.uploadStagingMinBytes, lgh::RendererOptions{}.uploadStagingMinBytes);
  lgh::Renderer renderer(opts);
  const auto results = renderHintedFirst(renderer, frames);
  ASSERT_EQ(results.size(), 2U);
  EXPECT_EQ(uploadOf(results[0]), "render_thread");
  EXPECT_EQ(uploadOf(results[1]), "staged");
}

TEST(UploadStaging, StagedBytesAreHeldUntilTheirScenesAreDrawnOrTheRendererGoes) {
  const std::vector<std::string> hinted = {"BoxTextured-glTF/BoxTextured.gltf",
                                           "ClearCoat-glTF/ClearCoatTest.gltf",
                                           "BoxBadNormals-glTF-Binary/BoxBadNormals.glb"};
  {
    lgh::Renderer renderer(options(64LL << 20));
    for (const std::string& asset : hinted) {
      renderer.prefetch(lgh::parseRenderRequest(thumbnailRequest(asset, false)));
    }
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (renderer.sceneCacheStats().stagingBytesInUse == 0 &&
           std::chrono::steady_clock::now() < giveUp) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_GT(renderer.sceneCacheStats().stagingBytesInUse, 0U) << "staged when parsed";
    // Drawn in hint order, each from its parse ahead; then the last again, from the cache.
    for (const std::string& asset : hinted) {
      renderer.submit(lgh::parseRenderRequest(thumbnailRequest(asset, false)));
    }
    renderer.submit(lgh::parseRenderRequest(thumbnailRequest(hinted.back(), true)));
    int frames = 0;
    while (std::optional<lgh::RenderResult> result = renderer.finish(true)) {
      EXPECT_EQ(uploadOf(*result), frames < 3 ? "staged" : "cached") << frames;
      ++frames;
    }
    EXPECT_EQ(frames, 4);
    renderer.submit(lgh::parseRenderRequest(thumbnailRequest(hinted.back(), false)));
    ASSERT_TRUE(renderer.finish(true));
    EXPECT_EQ(renderer.sceneCacheStats().stagingBytesInUse, 0U)
        << "every staged byte given back once its copies were done";
  }
  // Scenes staged and never drawn go back before the staging memory itself is freed.
  lgh::Renderer renderer(options(64LL << 20));
  for (const std::string& asset : hinted) {
    renderer.prefetch(lgh::parseRenderRequest(thumbnailRequest(asset, false)));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
}

}  // namespace
