// What the LGH lighting passes share: their settings, the hierarchy's buffers, the textures and
// buffers they write (the tile atlas, the reservoir, the shadow samples, the overdraw counter),
// the uniforms of glsl/include/lgh_shading.glsl (bindings: glsl/include/slots.glsl), and read-backs
// for tests and the benchmark. docs/LIGHTING.md describes the passes.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_objects.hpp"
#include "gl/slots.hpp"
#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "passes/brdf_features.hpp"
#include "passes/frame_targets.hpp"
#include "scene/camera.hpp"

namespace lgh {

struct LghLightingParams {
  float alpha = 1.0F;
  int startLevel = 1;        // lighting starts at S1, as the paper's GPU variant
  int sampleStartLevel = 2;  // S1 skipped for shadow sampling unless sampleS1
  int samples = 4;           // k
  std::uint32_t seed = 1;
  float shadowJitter = 0.0F;  // settings.lgh.shadow_jitter
  int interleave = 1;         // n: n x n tiles
  bool locked = false;
  bool overdraw = false;  // debug counter (slower: image atomics / stores per pixel)
  BrdfFeatures brdf;      // what the kernels' BRDF is compiled for (default: every model)

  static LghLightingParams fromSettings(const LghSettings& settings);
};

int interleaveFactor(InterleaveMode mode);

// The seed of a frame's shadow-sample random numbers (the reservoir, its jitter, the direct
// lights' soft-shadow jitter): settings.seed for frame 0, a hash of (seed, frame) for the others,
// so that accumulated frames carry independent noise.
std::uint32_t samplingSeed(const LghSettings& settings);

// The hierarchy as LghBuilder leaves it on the GPU.
struct LghHierarchyBuffers {
  GLuint gridLights = 0;
  GLuint levels = 0;
};

// Targets of the lighting passes. The atlas holds n x n tiles of ceil(W / n) x ceil(H / n)
// pixels (n = 1: the frame); everything per pixel (reservoir, samples, overdraw) is indexed by the
// full-resolution pixel, row 0 at the bottom as in GL.
class LghLightingTargets {
 public:
  // Reallocates what changed; the tile G-buffer only exists for n > 1.
  void resize(int width, int height, int interleave, int samples);
  // The accumulation framebuffer of the raster path with `depth` (the G-buffer's or the tiles')
  // as its depth attachment; rebuilt when the depth texture changes.
  GLuint accumulationFramebuffer(GLuint depth);
  void clearReservoir();
  void clearOverdraw();
  void clearLock();

  int width = 0;
  int height = 0;
  int interleave = 1;
  int tileWidth = 0;
  int tileHeight = 0;
  int samples = 0;
  int atlasWidth() const { return tileWidth * interleave; }
  int atlasHeight() const { return tileHeight * interleave; }

  gl::Texture accumulation{GL_TEXTURE_2D};  // RGBA32F atlas
  gl::Texture reservoirSum{GL_TEXTURE_2D};  // R32F: F per pixel
  gl::Texture lock{GL_TEXTURE_2D};          // R32UI: spin locks of the raster path
  gl::Texture overdraw{GL_TEXTURE_2D};      // R32UI: fragments / lights evaluated per pixel
  gl::SizedBuffer shadowSamples;            // vec4 per pixel and sample
  GBufferTargets tiles;                     // tile G-buffer (n > 1): position..material, depth

 private:
  gl::Framebuffer accumulationFramebuffer_;
  GLuint accumulationDepth_ = 0;
};

// Sets the uniforms of glsl/include/lgh_shading.glsl that `program` uses.
void setLightingUniforms(GLuint program, const LghLightingParams& params,
                         const LghLightingTargets& targets, const CameraMatrices& camera);
void bindHierarchy(const LghHierarchyBuffers& hierarchy);
void setUniform(GLuint program, const char* name, int value);
void setUniform(GLuint program, const char* name, GLuint value);
void setUniform(GLuint program, const char* name, float value);

// Programs compiled once per set of defines.
class ProgramCache {
 public:
  template <typename Build>
  GLuint get(const std::string& defines, Build&& build) {
    auto it = programs_.find(defines);
    if (it == programs_.end()) it = programs_.emplace(defines, build(defines)).first;
    return it->second.id();
  }

 private:
  std::map<std::string, gl::Program> programs_;
};

// Read-backs (wait for the GPU). Images come top row first like FloatImage; raw per-pixel
// buffers keep GL's order (row 0 at the bottom).
FloatImage readTextureImage(const gl::Texture& texture, int width, int height);
std::vector<float> readReservoirSums(const LghLightingTargets& targets);
std::vector<glm::vec4> readShadowSamples(const LghLightingTargets& targets);
std::vector<std::uint32_t> readOverdraw(const LghLightingTargets& targets);

}  // namespace lgh
