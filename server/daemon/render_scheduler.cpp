#include "render_scheduler.hpp"

#include <algorithm>
#include <functional>
#include <string_view>

#include <fmt/format.h>

namespace lghd {
namespace {

std::size_t hashBytes(const std::vector<std::uint8_t>& bytes) {
  return std::hash<std::string_view>{}(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// Whether `a` finishes sooner than `b` (ties: resident, then less loaded).
bool sooner(const WorkerEstimate& a, const WorkerEstimate& b) {
  if (a.finishSeconds() != b.finishSeconds()) return a.finishSeconds() < b.finishSeconds();
  if (a.resident != b.resident) return a.resident;
  return a.pendingSeconds < b.pendingSeconds;
}

}  // namespace

std::optional<std::size_t> chooseWorker(const std::vector<WorkerEstimate>& workers) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < workers.size(); ++i) {
    if (!workers[i].schedulable) continue;
    if (!best || sooner(workers[i], workers[*best])) best = i;
  }
  return best;
}

std::string sceneKey(const lgh::SceneSource& scene) {
  using Kind = lgh::SceneSource::Kind;
  switch (scene.kind) {
    case Kind::Builtin:
      return fmt::format("builtin:{}", lgh::enumName(scene.builtin));
    case Kind::AssetPath:
      return "path:" + scene.assetPath;
    case Kind::InlineGlb:
      return fmt::format("glb:{}:{:x}", scene.glbBytes.size(), hashBytes(scene.glbBytes));
    case Kind::UploadedGltf: {
      std::size_t hash = std::hash<std::string>{}(scene.gltfFileName);
      for (const auto& [name, bytes] : scene.uploadedFiles) {
        hash = hash * 31 + std::hash<std::string>{}(name)*17 + hashBytes(bytes);
      }
      return fmt::format("gltf:{:x}", hash);
    }
  }
  return "unknown";
}

bool ResidentScenes::contains(const std::string& key) const {
  return std::find(keys_.begin(), keys_.end(), key) != keys_.end();
}

void ResidentScenes::touch(const std::string& key) {
  keys_.remove(key);
  keys_.push_front(key);
  while (keys_.size() > capacity_) keys_.pop_back();
}

void ResidentScenes::limit(std::size_t count) {
  capacity_ = std::max<std::size_t>(count, 1);
  while (keys_.size() > capacity_) keys_.pop_back();
}

}  // namespace lghd
