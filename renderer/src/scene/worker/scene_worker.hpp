// The renderer's side of the scene parser worker (lgh/scene_worker.hpp): one child process that
// parses untrusted assets, started on construction, restarted after it dies. A load that crashes
// it, runs past the time limit or outgrows its memory limit fails that load with an lgh::Error,
// and the next load gets a fresh worker. Loads from several threads (the render thread and scene
// prefetches) take turns.
#pragma once

#include <sys/types.h>

#include <memory>
#include <mutex>
#include <string>

#include "lgh/renderer_options.hpp"
#include "scene/worker/scene_wire.hpp"

namespace lgh::worker {

class SharedMapping;

class SceneWorker {
 public:
  explicit SceneWorker(SceneWorkerOptions options);
  ~SceneWorker();
  SceneWorker(const SceneWorker&) = delete;
  SceneWorker& operator=(const SceneWorker&) = delete;

  // Throws lgh::Error: the loader's own, TooLarge past the time or memory limit, Invalid when the
  // asset crashed the worker, Unavailable when no worker can be started.
  Scene load(const LoadJob& job);

  pid_t pid() const { return pid_; }
  // Whether the running worker's answers come in its answer arena (when they fit).
  bool hasAnswerArena() const { return answers_ != nullptr; }

 private:
  void start();
  // Ends the worker: closes its socket, kills it when `kill` (else lets it exit), reaps it.
  // Returns how it ended, for messages ("exit 0", "signal 11 (Segmentation fault)").
  std::string stop(bool kill);
  LoadOutcome exchange(const LoadJob& job, const std::string& displayName);
  // Gives the new worker the memory its answers are written into when they fit (answers_).
  void offerAnswerArena();

  SceneWorkerOptions options_;
  std::mutex mutex_;  // one load at a time
  pid_t pid_ = -1;
  int socket_ = -1;
  std::unique_ptr<SharedMapping> answers_;  // the answer arena, mapped read-only
};

}  // namespace lgh::worker
