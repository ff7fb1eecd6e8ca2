// Drawing scene surfaces with their materials, shared by the G-buffer pass and the forward pass of
// blended surfaces: which program variant a material needs, its uniforms and textures (the
// uniforms of glsl/include/material_sampling.glsl, texture unit = slot), the frame's uniforms and
// one draw call.
#pragma once

#include <array>
#include <cstdint>

#include "lgh/request.hpp"
#include "passes/surface_programs.hpp"
#include "scene/camera.hpp"
#include "scene/gpu_scene.hpp"

namespace lgh {

// The model a draw shades with: lines and points without normals are unlit whatever their
// material says.
MaterialModel effectiveModel(const Material& material, bool unlit);

// The kMaterial* features (passes/surface_programs.hpp) the G-buffer shader needs for this draw.
std::uint32_t materialFeatures(const Material& material, const GpuScene::DrawItem& item);

// Whether the material's surface is displacement-mapped (drawn as tessellated patches, its
// positions moved off the mesh's).
bool displacedMaterial(const Material& material);

SurfaceProgramKey surfaceProgramKey(const Material& material, const GpuScene::DrawItem& item,
                                    bool forward);

// What every surface program of a frame shares.
struct SurfaceFrame {
  const CameraMatrices* camera = nullptr;
  const PrimitiveSettings* primitives = nullptr;
  int width = 0;
  int height = 0;
  int lightCount = 0;
  float ambient = 0.0F;
  float maxTessellationLevel = 64.0F;  // the device's GL_MAX_TESS_GEN_LEVEL
};
void setSurfaceFrameUniforms(SurfaceProgram& program, const SurfaceFrame& frame, bool pointDisk);

// The state that bindMaterial and drawSurface set last in a pass (unknown at first), so that they
// set only what changes between consecutive draws.
struct SurfaceDrawState {
  int cull = -1;  // -1 unknown, 0 off, 1 on
  GLenum frontFace = GL_NONE;
  GLuint vertexArray = ~0U;  // ~0: unknown
  bool texturesKnown = false;
  std::array<GLuint, kMaterialTextureSlots> textures{};  // by unit (= material slot)
  std::array<GLuint, kMaterialTextureSlots> samplers{};
};

// Sets the material uniforms of `program` (those that changed) and binds the material's textures
// and samplers (the units that changed).
void bindMaterial(SurfaceProgram& program, const Material& material, GpuScene& gpuScene, bool unlit,
                  SurfaceDrawState& state);

// One draw item: its transforms, face culling (double-sided materials and lines and points are
// not culled), and the draw call (GL_PATCHES when displaced).
void drawSurface(SurfaceProgram& program, const GpuScene::DrawItem& item, const Material& material,
                 bool displaced, SurfaceDrawState& state);

// Unbinds the samplers of the material slots.
void unbindMaterialSamplers();

}  // namespace lgh
