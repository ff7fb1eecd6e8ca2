// The GL worker (RendererOptions::glWorker, docs/ARCHITECTURE.md "GL worker"): a second context
// in the render context's share group, on a thread of its own, that uploads scenes parsed ahead
// and frees evicted ones. On whichever context path the suite runs (egl-device, surfaceless or
// osmesa: .ci/run runs it on each):
//  - what the worker writes into a buffer is what the render context reads, after its fence;
//  - thumbnails of real assets, scenes prefetched and uploaded on the worker, have the pixels of
//    the same frames uploaded on the render thread, and say where they were uploaded;
//  - evicted scenes' GL objects are freed (the live counts come back), and a renderer destroyed
//    with uploads ahead never drawn frees them too.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_helpers.hpp"
#include "gl/gl_objects.hpp"
#include "gl/gl_worker.hpp"
#include "gl/readback_buffers.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;
using lgh::test::pixelBytes;
using lgh::test::renderHintedFirst;
using lgh::test::thumbnailRequest;

lgh::RendererOptions options(bool glWorker) {
  lgh::RendererOptions opts = lgh::test::rendererOptions();
  opts.assetRoot = lgh::test::assimpGltfDir();
  opts.glWorker = glWorker;
  opts.uploadStagingBytes = 0;  // the worker's own upload, and no scene_upload decision without it
  opts.sceneCacheBytes = 0;     // every new scene evicts the one before
  return opts;
}

// Textured, untextured, many primitives, and one repeated after others.
const std::vector<std::string>& assets() {
  static const std::vector<std::string> list = {
      "BoxTextured-glTF/BoxTextured.gltf", "BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
      "ClearCoat-glTF/ClearCoatTest.gltf", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
      "BoxTextured-glTF/BoxTextured.gltf"};
  return list;
}

std::array<std::int64_t, 2> liveBuffersAndTextures() {
  const auto live = lgh::gl::liveObjects();
  return {live[static_cast<std::size_t>(lgh::gl::ObjectKind::Buffer)],
          live[static_cast<std::size_t>(lgh::gl::ObjectKind::Texture)]};
}

// The worker frees in its own time: polls until the counts are `expected`, for up to 10 s.
std::array<std::int64_t, 2> settleAt(const std::array<std::int64_t, 2>& expected) {
  const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  std::array<std::int64_t, 2> live = liveBuffersAndTextures();
  while (live != expected && std::chrono::steady_clock::now() < giveUp) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    live = liveBuffersAndTextures();
  }
  return live;
}

TEST(GlWorker, TheRenderContextReadsWhatTheWorkerUploaded) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  lgh::gl::Worker worker(context->createShared(), &context->api());
  EXPECT_NE(worker.info().contextPath.find("shared"), std::string::npos)
      << worker.info().contextPath;
  EXPECT_TRUE(worker.sharesCurrentContext()) << "the render context is current here";
  const std::vector<std::uint32_t> values = {7, 11, 13, 0xdeadbeef};
  struct Uploaded {
    lgh::gl::Buffer buffer;
    lgh::gl::Fence fence;
  };
  Uploaded uploaded =
      worker
          .run([&] {
            EXPECT_TRUE(worker.sharesCurrentContext());
            Uploaded made;
            glNamedBufferStorage(made.buffer.id(), static_cast<GLsizeiptr>(values.size() * 4),
                                 values.data(), 0);
            made.fence = lgh::gl::Fence::insert();
            return made;
          })
          .get();
  uploaded.fence.queueWait();
  std::vector<std::uint32_t> read(values.size(), 0);
  glGetNamedBufferSubData(uploaded.buffer.id(), 0, static_cast<GLsizeiptr>(read.size() * 4),
                          read.data());
  EXPECT_EQ(read, values);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // A task's exception comes back through its future; the worker goes on.
  auto failed = worker.run([]() -> int { throw std::runtime_error("task failed"); });
  EXPECT_THROW(failed.get(), std::runtime_error);
  EXPECT_EQ(worker.run([] { return 42; }).get(), 42);
}

TEST(GlWorker, ScenesUploadedAheadDrawAsScenesUploadedOnTheRenderThread) {
  std::vector<json> frames;
  for (const std::string& asset : assets()) {
    frames.push_back(thumbnailRequest(asset, true));
    frames.push_back(thumbnailRequest(asset, false));  // the same scene, drawn again at once
  }
  lgh::Renderer onWorker(options(true));
  lgh::Renderer onRenderThread(options(false));
  const auto ahead = renderHintedFirst(onWorker, frames);
  const auto here = renderHintedFirst(onRenderThread, frames);
  ASSERT_EQ(ahead.size(), frames.size());
  ASSERT_EQ(here.size(), frames.size());
  int uploadedOnWorker = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + frames[i].dump());
    EXPECT_EQ(pixelBytes(ahead[i]), pixelBytes(here[i]));
    EXPECT_EQ(here[i].decisions.count("scene_upload"), 0U) << "no worker, no decision";
    const std::string& upload = ahead[i].decisions.at("scene_upload");
    if (i % 2 == 1) {
      EXPECT_EQ(upload, "cached") << "the second view of a scene draws the cached upload";
      continue;
    }
    // A scene parsed ahead is uploaded ahead; one whose hint found no room in the look-ahead
    // (three parses in process) is parsed and uploaded when drawn.
    const bool prefetched = ahead[i].decisions.count("scene_parse") == 1;
    EXPECT_EQ(upload, prefetched ? "gl_worker" : "render_thread");
    if (upload == "gl_worker") {
      ++uploadedOnWorker;
      EXPECT_GT(ahead[i].timings.get("upload ahead"), 0.0);
    }
  }
  EXPECT_GE(uploadedOnWorker, 3);
}

TEST(GlWorker, EvictedScenesAndUploadsAheadNeverDrawnAreFreed) {
  const std::array<std::int64_t, 2> before = liveBuffersAndTextures();
  {
    lgh::Renderer renderer(options(true));
    std::vector<json> frames;
    for (const std::string& asset : assets()) frames.push_back(thumbnailRequest(asset, true));
    // The same frames twice: the frames' own objects (targets, ray and read-back buffers) are
    // made by the first run; both end with the cache holding assets().back()'s scene alone.
    renderHintedFirst(renderer, frames);
    const std::array<std::int64_t, 2> afterFirst = settleAt(liveBuffersAndTextures());
    renderHintedFirst(renderer, frames);
    EXPECT_EQ(settleAt(afterFirst), afterFirst)
        << "every evicted scene's buffers and textures were freed on the worker";
    // Hinted, parsed and uploaded ahead, never drawn: freed with the renderer.
    for (const std::string& asset : assets()) {
      renderer.prefetch(lgh::parseRenderRequest(thumbnailRequest(asset, false)));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(liveBuffersAndTextures(), before);
}

}  // namespace
