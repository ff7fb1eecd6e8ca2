// The scene parser processes (scene/worker/scene_worker_pool.hpp) serve loads in the order of
// their turns, taken when the scenes are hinted, whatever order the prefetch threads reach the pool
// in; a turn dropped unused lets the next one go. A worker's answers come the same whether they
// travel in its answer arena or in memory of their own. The worker process is lgh-bench, which
// answers --scene-parser-worker as lghd does, parsing real assimp test models.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "lgh/request.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/worker/scene_worker.hpp"
#include "scene/worker/scene_worker_pool.hpp"
#include "scene_compare.hpp"
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

lgh::worker::LoadJob assetJob(const std::string& path) {
  lgh::SceneSource source;
  source.kind = lgh::SceneSource::Kind::AssetPath;
  source.assetPath = path;
  return {source, lgh::test::assimpGltfDir(), {}, {}};
}

lgh::worker::LoadJob boxJob() { return assetJob("BoxTextured-glTF/BoxTextured.gltf"); }

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

// Many turns at once over three workers, their loads started in a shuffled order and every
// fifth turn dropped unused: each waiting load is woken only when its own turn comes (the pool
// wakes no other), so a wake lost anywhere would leave loads waiting for ever. Every load must
// finish, with its scene.
TEST(SceneWorkerPool, ManyTurnsOverSeveralWorkersAllFinishWhateverOrderTheyArriveIn) {
  lgh::SceneWorkerOptions options = workerOptions();
  options.processes = 3;
  SceneWorkerPool pool(options);
  constexpr int kTurns = 30;
  std::vector<std::optional<SceneWorkerPool::Turn>> turns;
  turns.reserve(kTurns);
  for (int i = 0; i < kTurns; ++i) turns.emplace_back(pool.reserveTurn());
  std::vector<int> order(kTurns);
  for (int i = 0; i < kTurns; ++i) order[static_cast<std::size_t>(i)] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  const std::vector<std::string> assets = {"BoxTextured-glTF/BoxTextured.gltf",
                                           "cameras/Cameras.gltf",
                                           "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"};
  std::vector<std::future<std::string>> names(kTurns);
  for (const int i : order) {
    auto& turn = turns[static_cast<std::size_t>(i)];
    if (i % 5 == 2) {
      turn.reset();  // dropped unused
      continue;
    }
    const std::string& asset = assets[static_cast<std::size_t>(i) % assets.size()];
    names[static_cast<std::size_t>(i)] =
        std::async(std::launch::async, [&pool, asset, mine = std::move(*turn)]() mutable {
          return pool.load(assetJob(asset), std::move(mine)).name;
        });
    turn.reset();
  }
  for (int i = 0; i < kTurns; ++i) {
    auto& name = names[static_cast<std::size_t>(i)];
    if (!name.valid()) continue;
    ASSERT_EQ(name.wait_for(std::chrono::seconds(60)), std::future_status::ready)
        << "turn " << i << " never got a worker";
    const std::string& asset = assets[static_cast<std::size_t>(i) % assets.size()];
    const lgh::worker::LoadJob job = assetJob(asset);
    EXPECT_EQ(name.get(),
              lgh::loadSceneSource(job.source, job.assetRoot, job.limits, job.options).name)
        << "turn " << i;
  }
}

// Large and small answers in turn, through one worker each: with the default arena (every answer
// fits), with one that only the small ones fit (the large ones in a sealed memfd each), and with
// none. Each load gives the scene this process loads itself, so neither the arena's reuse nor the
// switch between the two ways mixes up answers.
TEST(SceneWorker, AnswersInTheArenaAndInMemoryOfTheirOwnAreTheSameScenes) {
  const std::vector<std::string> assets = {
      "ClearCoat-glTF/ClearCoatTest.gltf", "BoxTextured-glTF/BoxTextured.gltf",
      "draco/2CylinderEngine.gltf", "BoxTextured-glTF/BoxTextured.gltf",
      "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"};
  for (const std::size_t arenaBytes :
       {lgh::SceneWorkerOptions{}.answerArenaBytes, std::size_t{1} << 20, std::size_t{0}}) {
    SCOPED_TRACE("answer arena of " + std::to_string(arenaBytes) + " bytes");
    lgh::SceneWorkerOptions options = workerOptions();
    options.answerArenaBytes = arenaBytes;
    lgh::worker::SceneWorker worker(options);
    EXPECT_EQ(worker.hasAnswerArena(), arenaBytes > 0);
    for (const std::string& asset : assets) {
      SCOPED_TRACE(asset);
      const lgh::worker::LoadJob job = assetJob(asset);
      const lgh::Scene here =
          lgh::loadSceneSource(job.source, job.assetRoot, job.limits, job.options);
      lgh::test::expectSameScene(here, worker.load(job));
    }
  }
}

}  // namespace
