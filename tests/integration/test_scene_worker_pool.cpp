// The scene parser processes (scene/worker/scene_worker_pool.hpp) serve loads in the order of
// their turns, taken when the scenes are hinted, whatever order the prefetch threads reach the pool
// in; a turn dropped unused lets the next one go. The worker process is lgh-bench, which answers
// --scene-parser-worker as lghd does, parsing a real assimp test model.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <string>
#include <thread>

#include "lgh/request.hpp"
#include "scene/worker/scene_worker_pool.hpp"
#include "test_support.hpp"

namespace {

using lgh::worker::SceneWorkerPool;

lgh::SceneWorkerOptions workerOptions() {
  lgh::SceneWorkerOptions options;
  options.executable = LGH_SCENE_WORKER_EXE;
  options.arguments = {"--scene-parser-worker"};
  options.processes = 1;
  return options;
}

lgh::worker::LoadJob boxJob() {
  lgh::SceneSource source;
  source.kind = lgh::SceneSource::Kind::AssetPath;
  source.assetPath = "BoxTextured-glTF/BoxTextured.gltf";
  return {source, lgh::test::assimpGltfDir(), {}, {}};
}

TEST(SceneWorkerPool, ALaterTurnWaitsForTheEarlierOnesEvenWithAnIdleWorker) {
  SceneWorkerPool pool(workerOptions());
  std::optional<SceneWorkerPool::Turn> first(pool.reserveTurn());
  std::optional<SceneWorkerPool::Turn> second(pool.reserveTurn());
  SceneWorkerPool::Turn third = pool.reserveTurn();
  std::atomic<bool> thirdDone{false};
  std::string thirdName;
  std::thread late([&] {
    thirdName = pool.load(boxJob(), std::move(third)).name;
    thirdDone = true;
  });
  // The worker is idle, but turns 1 and 2 come first: the third load must not start.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(thirdDone) << "a later turn was served before an earlier one";
  const lgh::Scene scene = pool.load(boxJob(), std::move(*first));  // turn 1, served now
  EXPECT_FALSE(scene.meshes.empty());
  first.reset();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(thirdDone) << "turn 2, neither used nor dropped, was skipped";
  second.reset();  // dropped unused: turn 3 goes
  late.join();
  EXPECT_TRUE(thirdDone);
  EXPECT_EQ(thirdName, scene.name);
}

TEST(SceneWorkerPool, ALoadWithoutATurnQueuesBehindTheTurnsTakenBeforeIt) {
  SceneWorkerPool pool(workerOptions());
  std::optional<SceneWorkerPool::Turn> hinted(pool.reserveTurn());
  std::atomic<bool> done{false};
  std::thread drawn([&] {
    pool.load(boxJob());
    done = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(done);
  hinted.reset();
  drawn.join();
  EXPECT_TRUE(done);
}

}  // namespace
