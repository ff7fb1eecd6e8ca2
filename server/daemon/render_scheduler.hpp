// Which render worker (GPU) takes a render: the one that will finish it soonest, by an estimate
// that knows each worker's queued work and whether the scene is resident in its scene cache.
//
//   finish(w) = pending(w) + (resident(scene, w) ? hit(w) : miss(w))
//
// pending(w) is the estimated seconds of what w holds (queued and in progress); hit and miss are
// w's running averages of a render whose scene was, or was not, in its cache. A worker holding
// the scene is chosen unless another, less loaded one finishes sooner even with the upload: the
// affinity is kept exactly while it does not cost more than it saves. Ties go to the worker
// holding the scene, then to the less loaded one, then to the lower index. No GL here: the
// choice is tested alone (tests/daemon/test_render_scheduler.cpp).
#pragma once

#include <cstddef>
#include <list>
#include <optional>
#include <string>
#include <vector>

#include "lgh/request.hpp"

namespace lghd {

// A worker as the scheduler sees it when it chooses.
struct WorkerEstimate {
  bool schedulable = false;   // ready, and not being rebuilt
  double pendingSeconds = 0;  // estimated work it holds
  double hitSeconds = 0.05;   // a render whose scene is in its cache
  double missSeconds = 0.1;   // a render that loads and uploads its scene
  bool resident = false;      // the render's scene is (as far as it knows) in its cache

  double finishSeconds() const { return pendingSeconds + renderSeconds(); }
  double renderSeconds() const { return resident ? hitSeconds : missSeconds; }
};

// The worker that finishes soonest; none when no worker is schedulable.
std::optional<std::size_t> chooseWorker(const std::vector<WorkerEstimate>& workers);

// What identifies a request's scene for affinity: the built-in scene's name, the asset path, or
// a hash of the uploaded bytes. Cheap, and equal for requests that the scene cache would share
// (it keys by content; two paths to one file are two keys here, which only costs affinity).
std::string sceneKey(const lgh::SceneSource& scene);

// The scenes a worker rendered last, most recent first, as many as its scene cache holds: the
// scheduler's view of what is resident there (the cache evicts by LRU too).
class ResidentScenes {
 public:
  bool contains(const std::string& key) const;
  void touch(const std::string& key);
  // Keeps at most `count` (at least one) keys.
  void limit(std::size_t count);
  void clear() { keys_.clear(); }

 private:
  std::list<std::string> keys_;
  std::size_t capacity_ = 1;
};

}  // namespace lghd
