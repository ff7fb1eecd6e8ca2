// The scene cache's look-ahead (Renderer::prefetch, scene/scene_cache.hpp) through a Renderer on
// llvmpipe: a hinted scene is parsed ahead and the frame that draws it says so
// ("scene_parse": "prefetched"); with the cache off, an asset hinted twice within the look-ahead
// (a batch that repeats it) is parsed ahead for both of its draws, not only for the first, and
// both parses start at their hints (scene/scene_cache.hpp directly).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "lgh/renderer.hpp"
#include "scene/scene_cache.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

lgh::RenderRequest thumbnailOf(const std::string& asset) {
  return lgh::parseRenderRequest(json{{"scene", {{"asset", asset}}},
                                      {"settings", {{"shadows", "off"}}},
                                      {"output", {{"width", 32}, {"height", 32}}}});
}

bool parsedAhead(const lgh::RenderResult& result) {
  const auto parse = result.decisions.find("scene_parse");
  return parse != result.decisions.end() && parse->second == "prefetched";
}

TEST(ScenePrefetch, AnAssetHintedTwiceIsParsedAheadForBothDrawsWithTheCacheOff) {
  lgh::RendererOptions options = lgh::test::rendererOptions();
  options.assetRoot = lgh::test::assimpGltfDir();
  options.sceneCacheBytes = 0;  // the cache keeps only the scene drawn last
  lgh::Renderer renderer(options);
  const lgh::RenderRequest box = thumbnailOf("BoxTextured-glTF/BoxTextured.gltf");
  const lgh::RenderRequest normals = thumbnailOf("BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  for (const lgh::RenderRequest* hinted : {&box, &normals, &box}) renderer.prefetch(*hinted);

  const lgh::RenderResult first = renderer.render(box);
  const lgh::RenderResult between = renderer.render(normals);
  const lgh::RenderResult again = renderer.render(box);
  EXPECT_TRUE(parsedAhead(first));
  EXPECT_TRUE(parsedAhead(between));
  EXPECT_TRUE(parsedAhead(again)) << "the second hint of the asset was dropped";
  EXPECT_FALSE(again.sceneCacheHit);
  EXPECT_EQ(first.pixels.size(), again.pixels.size());
  // Each GL-timed pass also says what issuing it cost the render thread (cpu_ms).
  for (const lgh::TimingRow& row : again.timings.rows) {
    if (row.name == "gbuffer") EXPECT_GE(row.cpuMilliseconds, 0.0);
    if (row.clock == lgh::TimingRow::Clock::Cpu) EXPECT_LT(row.cpuMilliseconds, 0.0) << row.name;
  }
  EXPECT_GE(again.timings.get("gbuffer"), 0.0);
}

TEST(ScenePrefetch, AWarmCacheParsesARepeatedAssetOnce) {
  lgh::RendererOptions options = lgh::test::rendererOptions();
  options.assetRoot = lgh::test::assimpGltfDir();
  lgh::Renderer renderer(options);
  const lgh::RenderRequest box = thumbnailOf("BoxTextured-glTF/BoxTextured.gltf");
  renderer.prefetch(box);
  renderer.prefetch(box);
  EXPECT_TRUE(parsedAhead(renderer.render(box)));
  const lgh::RenderResult again = renderer.render(box);
  EXPECT_TRUE(again.sceneCacheHit);
  EXPECT_EQ(renderer.sceneCacheStats().misses, 1U);
}

// The cache's own view: which hints start a parse. With the cache off, the repeat of an asset
// after another one gets its parse at its hint (a parse started only when the first draw took its
// own had too little time on the GPU machine); the next draw of the same asset gets none (the
// cache's newest scene serves it). With the cache on, one parse serves every hint of a scene.
class ScenePrefetchHints : public ::testing::Test {
 protected:
  void SetUp() override {
    options_ = lgh::test::rendererOptions();
    options_.assetRoot = lgh::test::assimpGltfDir();
    context_ = lgh::GlContext::create(options_);
  }
  static lgh::SceneSource asset(const std::string& path) { return thumbnailOf(path).scene; }
  lgh::RendererOptions options_;
  std::unique_ptr<lgh::GlContext> context_;
};

TEST_F(ScenePrefetchHints, WithTheCacheOffEachDrawOfAnotherSceneHasAParseFromItsHint) {
  options_.sceneCacheBytes = 0;
  lgh::SceneCache cache(options_);
  const lgh::SceneSource box = asset("BoxTextured-glTF/BoxTextured.gltf");
  const lgh::SceneSource normals = asset("BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  for (const lgh::SceneSource* hinted : {&box, &normals, &box, &box}) cache.prefetch(*hinted);
  EXPECT_EQ(cache.pendingPrefetches(), 3U) << "box, normals, box again; not the box after it";
  for (const lgh::SceneSource* drawn : {&box, &normals, &box}) {
    const lgh::SceneCache::Lookup lookup = cache.get(*drawn);
    EXPECT_TRUE(lookup.prefetched);
    EXPECT_FALSE(lookup.hit);
  }
  EXPECT_TRUE(cache.get(box).hit);
  EXPECT_EQ(cache.pendingPrefetches(), 0U);
}

TEST_F(ScenePrefetchHints, AHintWithNoRoomLeftIsParsedWhenTheDrawBeforeItTakesItsParse) {
  options_.sceneCacheBytes = 0;
  lgh::SceneCache cache(options_);
  ASSERT_EQ(cache.maxPrefetches(), 3U) << "no parser processes: two ahead, and one more";
  const lgh::SceneSource box = asset("BoxTextured-glTF/BoxTextured.gltf");
  const lgh::SceneSource normals = asset("BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  const std::vector<const lgh::SceneSource*> batch{&box, &normals, &box, &normals};
  for (const lgh::SceneSource* hinted : batch) cache.prefetch(*hinted);
  EXPECT_EQ(cache.pendingPrefetches(), 3U);
  for (const lgh::SceneSource* drawn : batch) EXPECT_TRUE(cache.get(*drawn).prefetched);
  EXPECT_EQ(cache.pendingPrefetches(), 0U);
}

TEST_F(ScenePrefetchHints, WithTheCacheOnOneParseServesEveryHintOfAScene) {
  lgh::SceneCache cache(options_);
  const lgh::SceneSource box = asset("BoxTextured-glTF/BoxTextured.gltf");
  const lgh::SceneSource normals = asset("BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  for (const lgh::SceneSource* hinted : {&box, &normals, &box}) cache.prefetch(*hinted);
  EXPECT_EQ(cache.pendingPrefetches(), 2U);
  EXPECT_TRUE(cache.get(box).prefetched);
  EXPECT_TRUE(cache.get(normals).prefetched);
  EXPECT_TRUE(cache.get(box).hit);
  EXPECT_EQ(cache.stats().misses, 2U);
}

// What a hint's parse is guessed to cost by (lghd's render worker hints a batch's start smallest
// first): an asset file's size, an inline GLB's bytes, nothing for a built-in scene or a path
// that does not resolve.
TEST_F(ScenePrefetchHints, SourceBytesAreTheFileOrTheUploadsSize) {
  const lgh::SceneCache cache(options_);
  const std::string engine = "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  EXPECT_EQ(cache.sourceBytes(asset(engine)),
            std::filesystem::file_size(lgh::test::assimpGltfDir() / engine));
  lgh::SceneSource inline_;
  inline_.kind = lgh::SceneSource::Kind::InlineGlb;
  inline_.glbBytes.assign(1234, 0);
  EXPECT_EQ(cache.sourceBytes(inline_), 1234U);
  EXPECT_EQ(cache.sourceBytes(lgh::SceneSource{}), 0U);  // the built-in demo
  EXPECT_EQ(cache.sourceBytes(asset("no/such/file.glb")), 0U);
  EXPECT_EQ(cache.sourceBytes(asset("../outside.glb")), 0U);
}

}  // namespace
