// The scene parser worker's messages (scene_worker.hpp), as bytes: what to load (a SceneSource and
// its limits) one way, the loaded Scene or the lgh::Error the other. Plain little-endian binary of
// the structs' fields, written and read by the same binary (the worker is lghd itself), so no
// versioning; a reader still checks every length against what is left, because a worker that
// misbehaves must not be able to harm the daemon that reads its answer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene.hpp"

namespace lgh::worker {

struct LoadJob {
  SceneSource source;
  std::filesystem::path assetRoot;  // AssetPath sources resolve inside it
  SceneLoadLimits limits;
  SceneLoadOptions options;  // the pose, material variant and extension tolerance
};

// A message ready to be written: its size in bytes, and how to write it into that much memory
// (so that the sender can put it straight into shared memory).
struct Encoded {
  std::size_t size = 0;
  std::function<void(std::uint8_t* destination)> write;
};

// Encoded messages refer to the job or outcome they encode: keep it alive until written.
Encoded encodeJob(const LoadJob& job);
// Throws lgh::Error(Internal) for bytes that are not a whole, well-formed message.
LoadJob decodeJob(std::span<const std::uint8_t> bytes);

using LoadOutcome = std::variant<Scene, Error>;

Encoded encodeOutcome(const LoadOutcome& outcome);
// Throws lgh::Error(Internal) for bytes that are not a whole, well-formed message, or a scene
// whose indices point outside it, whose index lists do not fit their topology, or whose enums
// hold values the renderer does not know.
LoadOutcome decodeOutcome(std::span<const std::uint8_t> bytes);

}  // namespace lgh::worker
