#include "passes/lgh_lighting_common.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "lgh/error.hpp"

namespace lgh {
namespace {

gl::Texture makeTexture(GLenum format, int width, int height) {
  gl::Texture texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.id(), 1, format, std::max(width, 1), std::max(height, 1));
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

void checkComplete(GLuint framebuffer, const char* name) {
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error(ErrorCode::Internal,
                "framebuffer incomplete (status " + std::to_string(status) + ")", name);
  }
}

void allocateTileGBuffer(GBufferTargets& tiles, int width, int height) {
  tiles.position = makeTexture(GL_RGBA32F, width, height);
  tiles.normal = makeTexture(GL_RGBA16F, width, height);
  tiles.albedo = makeTexture(GL_SRGB8_ALPHA8, width, height);
  tiles.material = makeTexture(GL_RGBA8, width, height);
  tiles.layers = makeTexture(GL_RGBA32UI, width, height);
  tiles.depth = makeTexture(GL_DEPTH_COMPONENT32F, width, height);
  tiles.framebuffer = gl::Framebuffer();
  // Location 4 is the layers target here (the tiles carry no emission).
  const std::array<const gl::Texture*, 5> colors{&tiles.position, &tiles.normal, &tiles.albedo,
                                                 &tiles.material, &tiles.layers};
  std::array<GLenum, 5> buffers{};
  for (std::size_t i = 0; i < colors.size(); ++i) {
    buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    glNamedFramebufferTexture(tiles.framebuffer.id(), buffers[i], colors[i]->id(), 0);
  }
  glNamedFramebufferTexture(tiles.framebuffer.id(), GL_DEPTH_ATTACHMENT, tiles.depth.id(), 0);
  glNamedFramebufferDrawBuffers(tiles.framebuffer.id(), static_cast<GLsizei>(buffers.size()),
                                buffers.data());
  checkComplete(tiles.framebuffer.id(), "lgh tile gbuffer");
}

void clearTexture(const gl::Texture& texture, GLenum format, GLenum type) {
  glClearTexImage(texture.id(), 0, format, type, nullptr);
}

std::size_t pixelCount(const LghLightingTargets& targets) {
  return static_cast<std::size_t>(targets.width) * static_cast<std::size_t>(targets.height);
}

// PCG hash (as glsl/include/reservoir.glsl).
std::uint32_t pcgHash(std::uint32_t value) {
  const std::uint32_t state = value * 747796405U + 2891336453U;
  const std::uint32_t word = ((state >> ((state >> 28U) + 4U)) ^ state) * 277803737U;
  return (word >> 22U) ^ word;
}

}  // namespace

std::uint32_t samplingSeed(const LghSettings& settings) {
  if (settings.frame == 0) return settings.seed;
  return pcgHash(settings.seed ^ pcgHash(settings.frame + 0x9e3779b9U));
}

LghLightingParams LghLightingParams::fromSettings(const LghSettings& settings) {
  LghLightingParams params;
  params.alpha = settings.alpha;
  params.sampleStartLevel = settings.sampleS1 ? 1 : 2;
  params.samples = std::clamp(settings.shadowSamples, 1, 8);
  params.seed = samplingSeed(settings);
  params.shadowJitter = settings.shadowJitter;
  params.interleave = interleaveFactor(settings.interleave);
  params.locked = settings.lockedReservoir;
  return params;
}

int interleaveFactor(InterleaveMode mode) {
  switch (mode) {
    case InterleaveMode::None:
      return 1;
    case InterleaveMode::Tiles2x2:
      return 2;
    case InterleaveMode::Tiles4x4:
      return 4;
  }
  return 1;
}

void LghLightingTargets::resize(int newWidth, int newHeight, int newInterleave, int newSamples) {
  const bool sizeChanged = newWidth != width || newHeight != height;
  const bool atlasChanged = sizeChanged || newInterleave != interleave || tileWidth == 0;
  if (sizeChanged || reservoirSum.id() == 0 || width == 0) {
    width = newWidth;
    height = newHeight;
    reservoirSum = makeTexture(GL_R32F, width, height);
    lock = makeTexture(GL_R32UI, width, height);
    overdraw = makeTexture(GL_R32UI, width, height);
    clearLock();
  }
  if (atlasChanged) {
    interleave = newInterleave;
    tileWidth = (width + interleave - 1) / interleave;
    tileHeight = (height + interleave - 1) / interleave;
    accumulation = makeTexture(GL_RGBA32F, atlasWidth(), atlasHeight());
    accumulationFramebuffer_ = gl::Framebuffer();
    accumulationDepth_ = 0;
    if (interleave > 1) allocateTileGBuffer(tiles, atlasWidth(), atlasHeight());
  }
  samples = newSamples;
  shadowSamples.reserve(static_cast<GLsizeiptr>(pixelCount(*this) * samples * sizeof(glm::vec4)));
}

GLuint LghLightingTargets::accumulationFramebuffer(GLuint depth) {
  if (accumulationDepth_ != depth || accumulationFramebuffer_.id() == 0) {
    accumulationFramebuffer_ = gl::Framebuffer();
    const GLuint framebuffer = accumulationFramebuffer_.id();
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, accumulation.id(), 0);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
    checkComplete(framebuffer, "lgh accumulation");
    accumulationDepth_ = depth;
  }
  return accumulationFramebuffer_.id();
}

void LghLightingTargets::clearReservoir() {
  clearTexture(reservoirSum, GL_RED, GL_FLOAT);
  glClearNamedBufferSubData(
      shadowSamples.id(), GL_R32F, 0,
      static_cast<GLsizeiptr>(pixelCount(*this) * samples * sizeof(glm::vec4)), GL_RED, GL_FLOAT,
      nullptr);
}

void LghLightingTargets::clearOverdraw() {
  clearTexture(overdraw, GL_RED_INTEGER, GL_UNSIGNED_INT);
}
void LghLightingTargets::clearLock() { clearTexture(lock, GL_RED_INTEGER, GL_UNSIGNED_INT); }

void setUniform(GLuint program, const char* name, int value) {
  const GLint location = glGetUniformLocation(program, name);
  if (location >= 0) glProgramUniform1i(program, location, value);
}

void setUniform(GLuint program, const char* name, GLuint value) {
  const GLint location = glGetUniformLocation(program, name);
  if (location >= 0) glProgramUniform1ui(program, location, value);
}

void setUniform(GLuint program, const char* name, float value) {
  const GLint location = glGetUniformLocation(program, name);
  if (location >= 0) glProgramUniform1f(program, location, value);
}

void setLightingUniforms(GLuint program, const LghLightingParams& params,
                         const LghLightingTargets& targets, const CameraMatrices& camera) {
  setUniform(program, "uAlpha", params.alpha);
  setUniform(program, "uStartLevel", params.startLevel);
  setUniform(program, "uSampleStartLevel", params.sampleStartLevel);
  setUniform(program, "uSampleCount", params.samples);
  setUniform(program, "uSeed", static_cast<GLuint>(params.seed));
  setUniform(program, "uShadowJitter", params.shadowJitter);
  setUniform(program, "uInterleave", targets.interleave);
  auto set2i = [program](const char* name, int x, int y) {
    const GLint location = glGetUniformLocation(program, name);
    if (location >= 0) glProgramUniform2i(program, location, x, y);
  };
  set2i("uFrameSize", targets.width, targets.height);
  set2i("uTileSize", targets.tileWidth, targets.tileHeight);
  const GLint cameraLocation = glGetUniformLocation(program, "uCameraPosition");
  if (cameraLocation >= 0) {
    glProgramUniform3fv(program, cameraLocation, 1, glm::value_ptr(camera.position));
  }
}

void bindHierarchy(const LghHierarchyBuffers& hierarchy) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GRID_LIGHTS, hierarchy.gridLights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LEVELS, hierarchy.levels);
}

FloatImage readTextureImage(const gl::Texture& texture, int width, int height) {
  FloatImage image;
  image.width = width;
  image.height = height;
  const std::size_t rowFloats = static_cast<std::size_t>(width) * 4;
  std::vector<float> bottomUp(rowFloats * static_cast<std::size_t>(height));
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureSubImage(texture.id(), 0, 0, 0, 0, width, height, 1, GL_RGBA, GL_FLOAT,
                       static_cast<GLsizei>(bottomUp.size() * sizeof(float)), bottomUp.data());
  image.rgba.resize(bottomUp.size());
  for (int y = 0; y < height; ++y) {
    const float* source = bottomUp.data() + rowFloats * static_cast<std::size_t>(height - 1 - y);
    std::copy(source, source + rowFloats,
              image.rgba.data() + rowFloats * static_cast<std::size_t>(y));
  }
  return image;
}

std::vector<float> readReservoirSums(const LghLightingTargets& targets) {
  std::vector<float> sums(pixelCount(targets));
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glGetTextureImage(targets.reservoirSum.id(), 0, GL_RED, GL_FLOAT,
                    static_cast<GLsizei>(sums.size() * sizeof(float)), sums.data());
  return sums;
}

std::vector<glm::vec4> readShadowSamples(const LghLightingTargets& targets) {
  std::vector<glm::vec4> samples(pixelCount(targets) * static_cast<std::size_t>(targets.samples));
  const auto bytes = static_cast<GLsizeiptr>(samples.size() * sizeof(glm::vec4));
  // Through a staging buffer: NVIDIA moves a buffer that the CPU reads into host memory, which
  // would slow every later frame that writes it.
  gl::Buffer staging;
  glNamedBufferStorage(staging.id(), std::max<GLsizeiptr>(bytes, 16), nullptr, GL_MAP_READ_BIT);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glCopyNamedBufferSubData(targets.shadowSamples.id(), staging.id(), 0, 0, bytes);
  glGetNamedBufferSubData(staging.id(), 0, bytes, samples.data());
  return samples;
}

std::vector<std::uint32_t> readOverdraw(const LghLightingTargets& targets) {
  std::vector<std::uint32_t> counts(pixelCount(targets));
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glGetTextureImage(targets.overdraw.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                    static_cast<GLsizei>(counts.size() * sizeof(std::uint32_t)), counts.data());
  return counts;
}

}  // namespace lgh
