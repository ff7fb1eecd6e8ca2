// render_scheduler.hpp without GL: which worker the front queue gives a render (soonest finish,
// scene-cache affinity while it does not cost more than it saves), the scene keys that affinity
// compares, and the scheduler's bounded view of each cache.
#include <gtest/gtest.h>

#include <vector>

#include "render_scheduler.hpp"

namespace lghd {
namespace {

WorkerEstimate worker(double pending, bool resident = false, double hit = 0.1, double miss = 1.0) {
  WorkerEstimate estimate;
  estimate.schedulable = true;
  estimate.pendingSeconds = pending;
  estimate.hitSeconds = hit;
  estimate.missSeconds = miss;
  estimate.resident = resident;
  return estimate;
}

TEST(RenderScheduler, TheLeastLoadedWorkerTakesARenderNoneHolds) {
  EXPECT_EQ(chooseWorker({worker(2.0), worker(0.5), worker(1.0)}), 1U);
}

TEST(RenderScheduler, EqualWorkersGoToTheLowestIndex) {
  EXPECT_EQ(chooseWorker({worker(0.0), worker(0.0)}), 0U);
}

TEST(RenderScheduler, AWorkerHoldingTheSceneWinsWhileItsQueueCostsLessThanTheUpload) {
  // Worker 0 holds the scene: 0.5 + 0.1 = 0.6 against 0 + 1.0 on the idle worker 1.
  EXPECT_EQ(chooseWorker({worker(0.5, true), worker(0.0)}), 0U);
}

TEST(RenderScheduler, AffinityGivesWayWhenTheQueueCostsMoreThanItSaves) {
  // Worker 0 holds the scene but 2.0 s of work: 2.1 against 1.0 with the upload on worker 1.
  EXPECT_EQ(chooseWorker({worker(2.0, true), worker(0.0)}), 1U);
}

TEST(RenderScheduler, TiesGoToTheWorkerHoldingTheScene) {
  // 0.9 + 0.1 = 1.0 = 0 + 1.0: the resident worker keeps the upload off the other GPU.
  EXPECT_EQ(chooseWorker({worker(0.0), worker(0.9, true)}), 1U);
}

TEST(RenderScheduler, FasterGpusGetMoreWork) {
  // Same queue length in renders, but worker 1 renders twice as fast.
  EXPECT_EQ(chooseWorker({worker(1.0, false, 0.1, 1.0), worker(1.0, false, 0.05, 0.5)}), 1U);
}

TEST(RenderScheduler, WorkersOutOfSchedulingAreSkipped) {
  std::vector<WorkerEstimate> workers = {worker(0.0, true), worker(5.0)};
  workers[0].schedulable = false;  // rebuilding its context
  EXPECT_EQ(chooseWorker(workers), 1U);
  workers[1].schedulable = false;
  EXPECT_FALSE(chooseWorker(workers).has_value());
  EXPECT_FALSE(chooseWorker({}).has_value());
}

TEST(RenderScheduler, SceneKeysNameTheSceneNotTheRequest) {
  lgh::SceneSource demo;
  lgh::SceneSource path;
  path.kind = lgh::SceneSource::Kind::AssetPath;
  path.assetPath = "a/b.glb";
  lgh::SceneSource glb;
  glb.kind = lgh::SceneSource::Kind::InlineGlb;
  glb.glbBytes = {1, 2, 3};
  lgh::SceneSource sameGlb = glb;
  lgh::SceneSource otherGlb = glb;
  otherGlb.glbBytes = {1, 2, 4};
  EXPECT_EQ(sceneKey(demo), "builtin:demo");
  EXPECT_EQ(sceneKey(path), "path:a/b.glb");
  EXPECT_EQ(sceneKey(glb), sceneKey(sameGlb));
  EXPECT_NE(sceneKey(glb), sceneKey(otherGlb));
  lgh::SceneSource gltf;
  gltf.kind = lgh::SceneSource::Kind::UploadedGltf;
  gltf.gltfFileName = "m.gltf";
  gltf.uploadedFiles = {{"m.gltf", {1}}, {"m.bin", {2}}};
  lgh::SceneSource otherGltf = gltf;
  otherGltf.uploadedFiles["m.bin"] = {3};
  EXPECT_NE(sceneKey(gltf), sceneKey(otherGltf));
}

TEST(RenderScheduler, ResidentScenesKeepTheMostRecentAsManyAsTheCacheHolds) {
  ResidentScenes scenes;
  scenes.limit(2);
  scenes.touch("a");
  scenes.touch("b");
  scenes.touch("a");  // a is the most recent now
  scenes.touch("c");  // b goes
  EXPECT_TRUE(scenes.contains("a"));
  EXPECT_FALSE(scenes.contains("b"));
  EXPECT_TRUE(scenes.contains("c"));
  scenes.limit(0);  // at least one is kept
  EXPECT_TRUE(scenes.contains("c"));
  EXPECT_FALSE(scenes.contains("a"));
  scenes.clear();
  EXPECT_FALSE(scenes.contains("c"));
}

}  // namespace
}  // namespace lghd
