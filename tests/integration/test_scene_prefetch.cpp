// The scene cache's look-ahead (Renderer::prefetch, scene/scene_cache.hpp) through a Renderer on
// llvmpipe: a hinted scene is parsed ahead and the frame that draws it says so
// ("scene_parse": "prefetched"); with the cache off, an asset hinted twice within the look-ahead
// (a batch that repeats it) is parsed ahead for both of its draws, not only for the first.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "lgh/renderer.hpp"
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

}  // namespace
