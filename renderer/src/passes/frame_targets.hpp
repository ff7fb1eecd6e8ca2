// The textures one frame renders into, sized to the output. Passes read and write these; the
// renderer owns them and resizes them when the output size changes.
#pragma once

#include "gl/gl_objects.hpp"

namespace lgh {

// The G-buffer; glsl/include/gbuffer.glsl documents what each target holds. Readers bind them with
// bindGBuffer() (units 0..4 and LGH_GBUFFER_LAYERS_UNIT).
struct GBufferTargets {
  gl::Texture position{GL_TEXTURE_2D};  // RGBA32F: world xyz, w = coverage
  gl::Texture normal{GL_TEXTURE_2D};    // RGBA16F
  gl::Texture albedo{GL_TEXTURE_2D};    // SRGB8_ALPHA8: base colour, a = occlusion
  gl::Texture material{GL_TEXTURE_2D};  // RGBA8: metallic, roughness
  gl::Texture emissive{GL_TEXTURE_2D};  // RGBA16F
  gl::Texture layers{GL_TEXTURE_2D};    // RGBA32UI: material layer parameters (gbuffer.glsl)
  gl::Texture depth{GL_TEXTURE_2D};     // DEPTH_COMPONENT32F
  gl::Framebuffer framebuffer;
};

struct FrameTargets {
  int width = 0;
  int height = 0;
  GBufferTargets gbuffer;
  gl::Texture direct{GL_TEXTURE_2D};  // RGBA16F: direct lighting radiance
  gl::Framebuffer directFramebuffer;
  gl::Texture indirect{GL_TEXTURE_2D};  // RGBA16F: LGH lighting radiance
  gl::Framebuffer indirectFramebuffer;
  gl::Texture final{GL_TEXTURE_2D};  // RGBA32F: linear composite
  gl::Framebuffer finalFramebuffer;

  // Reallocates every target for this size (no-op when unchanged).
  void resize(int newWidth, int newHeight);
};

}  // namespace lgh
