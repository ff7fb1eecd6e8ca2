#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_targets.hpp"
#include "lgh/error.hpp"
#include "scene/gltf/gltf_loader.hpp"

namespace lgh::fuzz {
namespace {

using Files = std::map<std::string, std::vector<std::uint8_t>>;

// The model is everything before the first marker; each marker line names the file that follows
// it, up to the next marker.
Files splitSideFiles(std::string_view input) {
  Files files;
  std::string name = "model.gltf";
  for (;;) {
    const std::size_t marker = input.find(kSideFileMarker);
    const std::string_view content = input.substr(0, marker);
    files[name].assign(content.begin(), content.end());
    if (marker == std::string_view::npos) return files;
    input.remove_prefix(marker + kSideFileMarker.size());
    const std::size_t end = input.find('\n');
    name = std::string(input.substr(0, end));
    if (end == std::string_view::npos) return files;
    input.remove_prefix(end + 1);
  }
}

// Small limits keep each run fast and memory-bounded, and reach the limit checks.
SceneLoadLimits fuzzLimits() {
  SceneLoadLimits limits;
  limits.maxTriangles = 200'000;
  limits.maxTextureSize = 1024;
  limits.maxFileBytes = 8U << 20U;
  return limits;
}

}  // namespace

void gltfLoader(const std::uint8_t* data, std::size_t size) {
  const Files files = splitSideFiles(std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    (void)loadGltfFromMemory("model.gltf", files, fuzzLimits());
  } catch (const Error&) {
  }
  const std::vector<std::uint8_t>& model = files.at("model.gltf");
  // Animation sampling runs only for a request's scene.animation: pose assets that have any.
  const std::string_view text(reinterpret_cast<const char*>(model.data()), model.size());
  if (text.find("\"animations\"") != std::string_view::npos) {
    SceneLoadOptions posed;
    posed.animation = SceneAnimation{0, 0.75F};
    try {
      (void)loadGltfFromMemory("model.gltf", files, fuzzLimits(), posed);
    } catch (const Error&) {
    }
  }
  if (model.size() >= 4 &&
      std::string_view(reinterpret_cast<const char*>(model.data()), 4) == "glTF") {
    try {
      (void)loadGlbBytes(model, "inline.glb", fuzzLimits());
    } catch (const Error&) {
    }
  }
}

}  // namespace lgh::fuzz
