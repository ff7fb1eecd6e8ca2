#include "passes/frame_targets.hpp"

#include <array>

#include "lgh/error.hpp"

namespace lgh {
namespace {

gl::Texture makeTarget(GLenum format, int width, int height) {
  gl::Texture texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.id(), 1, format, width, height);
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

void checkComplete(const gl::Framebuffer& framebuffer, const char* name) {
  GLenum status = glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error(ErrorCode::Internal,
                "framebuffer incomplete (status " + std::to_string(status) + ")", name);
  }
}

gl::Framebuffer singleTargetFramebuffer(const gl::Texture& color, const char* name) {
  gl::Framebuffer framebuffer;
  glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  checkComplete(framebuffer, name);
  return framebuffer;
}

}  // namespace

void FrameTargets::resize(int newWidth, int newHeight) {
  if (newWidth == width && newHeight == height) return;
  surfaceTiles.reset();
  width = newWidth;
  height = newHeight;
  gbuffer.position = makeTarget(GL_RGBA32F, width, height);
  gbuffer.normal = makeTarget(GL_RGBA16F, width, height);
  gbuffer.albedo = makeTarget(GL_SRGB8_ALPHA8, width, height);
  gbuffer.material = makeTarget(GL_RGBA8, width, height);
  gbuffer.emissive = makeTarget(GL_RGBA16F, width, height);
  gbuffer.layers = makeTarget(GL_RGBA32UI, width, height);
  gbuffer.depth = makeTarget(GL_DEPTH_COMPONENT32F, width, height);
  gbuffer.framebuffer = gl::Framebuffer();
  const std::array<const gl::Texture*, 6> colors{&gbuffer.position, &gbuffer.normal,
                                                 &gbuffer.albedo,   &gbuffer.material,
                                                 &gbuffer.emissive, &gbuffer.layers};
  std::array<GLenum, 6> buffers{};
  for (size_t i = 0; i < colors.size(); ++i) {
    buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    glNamedFramebufferTexture(gbuffer.framebuffer.id(), buffers[i], colors[i]->id(), 0);
  }
  glNamedFramebufferTexture(gbuffer.framebuffer.id(), GL_DEPTH_ATTACHMENT, gbuffer.depth.id(), 0);
  glNamedFramebufferDrawBuffers(gbuffer.framebuffer.id(), static_cast<GLsizei>(buffers.size()),
                                buffers.data());
  checkComplete(gbuffer.framebuffer, "gbuffer");

  direct = makeTarget(GL_RGBA16F, width, height);
  directFramebuffer = singleTargetFramebuffer(direct, "direct");
  indirect = makeTarget(GL_RGBA16F, width, height);
  indirectFramebuffer = singleTargetFramebuffer(indirect, "indirect");
  for (OutputTarget& target : outputs) {
    target.framebuffer.reset();
    target.texture.reset();
  }
  scene.framebuffer.reset();
  scene.texture.reset();
}

OutputTarget& FrameTargets::output(OutputPixels pixels) {
  static constexpr GLenum kFormats[3] = {GL_RGBA8UI, GL_RGBA16F, GL_RGBA32F};
  const auto index = static_cast<std::size_t>(pixels);
  OutputTarget& target = outputs[index];
  if (target.texture.id() == 0) {
    target.texture = makeTarget(kFormats[index], width, height);
    target.framebuffer = singleTargetFramebuffer(target.texture, "output");
  }
  return target;
}

OutputTarget& FrameTargets::sceneLinear() {
  if (scene.texture.id() == 0) {
    scene.texture = makeTarget(GL_RGBA32F, width, height);
    scene.framebuffer = singleTargetFramebuffer(scene.texture, "scene");
  }
  return scene;
}

}  // namespace lgh
