// The textures one frame renders into, sized to the output. Passes read and write these; the
// renderer owns them and resizes them when the output size changes.
#pragma once

#include <array>
#include <optional>

#include "gl/gl_objects.hpp"
#include "passes/surface_tiles.hpp"

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
  // The framebuffer's draw buffers as the G-buffer pass set them last (none yet: all GL_NONE):
  // setting them changes the framebuffer, which the driver validates again at the next draw.
  std::array<GLenum, 6> drawBuffers{};
};

// What a frame is read back as, and the target the composite pass writes it to.
enum class OutputPixels { Display8, LinearHalf, LinearFloat };

struct OutputTarget {
  gl::Texture texture = gl::Texture::empty();
  gl::Framebuffer framebuffer = gl::Framebuffer::empty();
};

struct FrameTargets {
  int width = 0;
  int height = 0;
  GBufferTargets gbuffer;
  // The work-group tiles the G-buffer's surfaces can cover, as the G-buffer pass found them for
  // the frame it drew last (none known: every tile; a G-buffer written otherwise, as tests do,
  // leaves it so): passes whose output was cleared beforehand dispatch these alone.
  std::optional<FrameTiles> surfaceTiles;
  FrameTiles tilesWithSurfaces() const { return surfaceTiles.value_or(allTiles(width, height)); }
  gl::Texture direct{GL_TEXTURE_2D};  // RGBA16F: direct lighting radiance
  gl::Framebuffer directFramebuffer;
  gl::Texture indirect{GL_TEXTURE_2D};  // RGBA16F: LGH lighting radiance
  gl::Framebuffer indirectFramebuffer;
  // The composite's output, rows turned over (GL's first row is the image's top), made on first
  // use at each size: RGBA8UI display codes, RGBA16F or RGBA32F linear light.
  OutputTarget outputs[3];
  // RGBA32F linear light, rows as GL stores them, made on first use at each size: frames with
  // blended surfaces are composited here, the forward blend pass draws over it (depth-tested
  // against the G-buffer's depth) and the display pass turns it into output(pixels).
  OutputTarget scene;

  // Reallocates every target for this size (no-op when unchanged).
  void resize(int newWidth, int newHeight);
  OutputTarget& output(OutputPixels pixels);
  OutputTarget& sceneLinear();
};

}  // namespace lgh
