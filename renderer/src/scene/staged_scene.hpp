// A parsed scene's upload bytes copied into staging memory (gl/staging_memory.hpp) by the thread
// that parsed it, in the layout of GpuScene's buffers: every primitive's vertices in scene order,
// then every primitive's indices, then the RGBA8 pixels of each image a material samples that the
// upload takes as decoded (no block compression). GpuScene then uploads them as GPU copies.
#pragma once

#include <map>
#include <optional>

#include "gl/staging_memory.hpp"
#include "lgh/request.hpp"
#include "scene/scene.hpp"

namespace lgh {

struct StagedScene {
  gl::StagingMemory::Region region;
  GLuint buffer = 0;
  // Offsets in `buffer`.
  GLintptr vertices = 0;
  GLintptr indices = 0;
  std::map<int, GLintptr> images;  // by index into Scene::images
};

// On any thread. Nothing when the scene's bytes are fewer than `minBytes`, or when the memory has
// no span that large: the scene is uploaded from its own bytes then.
std::optional<StagedScene> stageScene(const Scene& scene, gl::StagingMemory& memory,
                                      TextureCompression compression, std::size_t minBytes = 0);

}  // namespace lgh
