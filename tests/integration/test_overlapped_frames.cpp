// Overlapped frames (RendererOptions::overlapShadowedFrames, docs/SHADOWS.md "Overlapped frames"):
// a shadowed frame's draw stops after its rays' hand-over, and its direct lighting, composite and
// read-back copy are issued after the next frame's G-buffer, in the other frame set and ray lane.
// On llvmpipe + lavapipe (staging transport):
//  - frames of different scenes, sizes and formats, split or whole, submitted back to back, give
//    the same pixels as the same frames issued whole, in submission order;
//  - which frames split: shadowed ones without LGH lighting or blended surfaces;
//  - a split frame left by itself is finished by finish(false) polling it as the oldest;
//  - a frame that fails to draw leaves the split frame before it intact.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame_helpers.hpp"
#include "lgh/base64.hpp"
#include "lgh/error.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;
using lgh::test::pixelBytes;

lgh::RendererOptions options(bool overlap) {
  lgh::RendererOptions opts = lgh::test::rendererOptions();
  opts.assetRoot = lgh::test::assimpGltfDir();
  opts.overlapShadowedFrames = overlap;
  return opts;
}

// A ground square and an occluder above it, lit from above by a point light at `lightX`.
json occluder(float lightX, int width, int height, const std::string& format) {
  std::vector<lgh::test::Position> positions;
  std::vector<std::uint32_t> indices;
  lgh::test::addSquare(positions, indices, 0.0F, 2.0F);
  lgh::test::addSquare(positions, indices, 1.0F, 0.25F);
  const auto glb = lgh::test::makeTriangleGlb(positions, indices);
  return {{"scene", {{"glb_base64", lgh::base64::encode(glb)}}},
          {"camera",
           {{"type", "look_at"},
            {"position", {0, 3, 0}},
            {"target", {0, 0, 0}},
            {"up", {0, 0, -1}},
            {"yfov", 45}}},
          {"lights", {{{"type", "point"}, {"position", {lightX, 2, 0}}, {"intensity", 10}}}},
          {"settings", {{"shadows", "on"}}},
          {"output", {{"width", width}, {"height", height}, {"format", format}}}};
}

json box(int width, int height) {
  return {{"scene", {{"asset", "BoxTextured-glTF/BoxTextured.gltf"}}},
          {"settings", {{"shadows", "on"}}},
          {"output", {{"width", width}, {"height", height}, {"format", "png"}}}};
}

// The sequence: split frames of different sizes and formats back to back, a frame without
// shadows, one with blended surfaces and one with LGH lighting between them (drawn whole).
std::vector<json> mixedSequence() {
  json unshadowed = box(40, 30);
  unshadowed["settings"]["shadows"] = "off";
  json blended = box(48, 40);
  blended["materials"] = {
      {{"match", {{"all", true}}}, {"parameters", {{"alpha_mode", "blend"}, {"alpha", 0.5}}}}};
  json lgh = {{"settings", {{"shadows", "on"}, {"lgh", {{"enabled", true}, {"vpl_count", 500}}}}},
              {"output", {{"width", 32}, {"height", 24}, {"format", "png"}}}};
  return {occluder(0.0F, 64, 64, "exr-float"),
          box(64, 48),
          occluder(0.4F, 80, 60, "png"),
          unshadowed,
          occluder(-0.4F, 64, 64, "exr-half"),
          blended,
          box(64, 48),
          lgh,
          occluder(0.2F, 48, 48, "png"),
          box(56, 56)};
}

std::vector<lgh::RenderResult> submitAll(lgh::Renderer& renderer, const std::vector<json>& frames) {
  std::vector<std::uint64_t> ids;
  ids.reserve(frames.size());
  for (const json& frame : frames) ids.push_back(renderer.submit(lgh::parseRenderRequest(frame)));
  std::vector<lgh::RenderResult> results;
  while (std::optional<lgh::RenderResult> result = renderer.finish(true)) {
    results.push_back(std::move(*result));
  }
  EXPECT_EQ(results.size(), ids.size());
  for (std::size_t i = 0; i < results.size() && i < ids.size(); ++i) {
    EXPECT_EQ(results[i].frameId, ids[i]) << "frames come back in submission order";
  }
  return results;
}

TEST(OverlappedFrames, SplitFramesGiveThePixelsOfWholeFrames) {
  const std::vector<json> frames = mixedSequence();
  lgh::Renderer overlapped(options(true));
  lgh::Renderer whole(options(false));
  const std::vector<lgh::RenderResult> split = submitAll(overlapped, frames);
  const std::vector<lgh::RenderResult> reference = submitAll(whole, frames);
  ASSERT_EQ(split.size(), frames.size());
  ASSERT_EQ(reference.size(), frames.size());
  const std::vector<std::string> expected = {"split", "split", "split", "whole", "split",
                                             "whole", "split", "whole", "split", "split"};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + frames[i]["output"].dump());
    EXPECT_EQ(split[i].decisions.at("frame_overlap"), expected[i]);
    EXPECT_EQ(reference[i].decisions.at("frame_overlap"), "whole");
    EXPECT_EQ(split[i].output.width, frames[i]["output"]["width"].get<int>());
    EXPECT_EQ(split[i].output.height, frames[i]["output"]["height"].get<int>());
    // Every pass of a split frame ran and was timed. A split frame has nothing to composite:
    // its direct lighting pass writes the output.
    for (const char* pass : {"gbuffer", "direct lighting", "readback"}) {
      EXPECT_GE(split[i].timings.get(pass), 0.0) << pass;
    }
    if (expected[i] == "split") EXPECT_LT(split[i].timings.get("composite"), 0.0);
    if (frames[i]["settings"]["shadows"] == "on") {
      EXPECT_GE(split[i].timings.get("shadow ray setup"), 0.0);
      EXPECT_GE(split[i].timings.get("shadow rays"), 0.0);
    }
    if (frames[i]["settings"].contains("lgh")) continue;  // float atomics: last bits vary
    EXPECT_EQ(pixelBytes(split[i]), pixelBytes(reference[i]));
  }
}

// Split frames whose rays go through staging copies (LGH_NO_PINNED_MEMORY; shadows/
// batch_transport.hpp: copied over, traced while GL draws on, copied back before the direct
// lighting) give the pixels of split frames whose rays stay in lavapipe's memory pinned into GL.
// Each test runs in a process of its own (ctest): the variable stays here.
TEST(OverlappedFrames, StagingSplitFramesGiveThePixelsOfPinnedOnes) {
  const std::vector<json> frames = mixedSequence();
  lgh::Renderer pinned(options(true));
  const std::vector<lgh::RenderResult> viaPinned = submitAll(pinned, frames);
  setenv("LGH_NO_PINNED_MEMORY", "1", 1);
  lgh::Renderer staging(options(true));
  const std::vector<lgh::RenderResult> viaStaging = submitAll(staging, frames);
  unsetenv("LGH_NO_PINNED_MEMORY");
  ASSERT_EQ(viaPinned.size(), frames.size());
  ASSERT_EQ(viaStaging.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + frames[i]["output"].dump());
    if (frames[i]["settings"]["shadows"] != "on") continue;
    EXPECT_EQ(viaPinned[i].decisions.at("shadow_transport"), "pinned");
    EXPECT_EQ(viaStaging[i].decisions.at("shadow_transport"), "staging");
    EXPECT_EQ(viaPinned[i].decisions.at("frame_overlap"),
              viaStaging[i].decisions.at("frame_overlap"));
    if (frames[i]["settings"].contains("lgh")) continue;  // float atomics: last bits vary
    EXPECT_EQ(pixelBytes(viaPinned[i]), pixelBytes(viaStaging[i]));
  }
}

TEST(OverlappedFrames, ASplitFrameLeftAloneIsFinishedByPolling) {
  lgh::Renderer renderer(options(true));
  renderer.submit(lgh::parseRenderRequest(box(32, 32)));
  std::optional<lgh::RenderResult> result;
  const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!(result = renderer.finish(false)) && std::chrono::steady_clock::now() < giveUp) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(result.has_value()) << "the split frame was never finished";
  EXPECT_EQ(result->decisions.at("frame_overlap"), "split");
  EXPECT_EQ(renderer.pendingFrames(), 0U);
}

TEST(OverlappedFrames, AFailedFrameLeavesTheSplitFrameBeforeItIntact) {
  lgh::Renderer renderer(options(true));
  lgh::Renderer whole(options(false));
  const json first = occluder(0.3F, 64, 64, "exr-float");
  const std::uint64_t id = renderer.submit(lgh::parseRenderRequest(first));
  json missing = box(32, 32);
  missing["scene"]["asset"] = "no/such/asset.gltf";
  EXPECT_THROW(renderer.submit(lgh::parseRenderRequest(missing)), lgh::Error);
  const std::uint64_t next = renderer.submit(lgh::parseRenderRequest(box(32, 32)));
  const std::optional<lgh::RenderResult> split = renderer.finish(true);
  ASSERT_TRUE(split.has_value());
  EXPECT_EQ(split->frameId, id);
  EXPECT_EQ(pixelBytes(*split), pixelBytes(whole.renderFrame(lgh::parseRenderRequest(first))));
  const std::optional<lgh::RenderResult> after = renderer.finish(true);
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(after->frameId, next);
  EXPECT_TRUE(renderer.healthy());
}

}  // namespace
