// Material parameters (lgh::MaterialParameters: a request's `materials`, a glTF material's
// extras.lgh) applied to scene materials, and the per-frame table of materials the G-buffer and
// forward passes draw with: the cached scene's materials with the request's overrides applied, so
// that overrides never change what the cache holds.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "lgh/material_settings.hpp"
#include "scene/scene.hpp"

namespace lgh {

// Turns a texture choice into a TextureRef; throws lgh::Error naming `pointer` when the scene has
// no such texture.
using TextureResolver =
    std::function<TextureRef(const TextureChoice& choice, const std::string& pointer)>;

// Applies what `parameters` sets to `material`, then checks that the result makes sense (a shading
// mode the model has, a height map for the height-based techniques). Errors are
// lgh::Error(Invalid) naming `pointer` + "/" + the field.
void applyMaterialParameters(const MaterialParameters& parameters, const TextureResolver& resolve,
                             Material& material, const std::string& pointer);

// The scene's textures by index (Scene::textures), for parameters given with a scene.
TextureResolver sceneTextureResolver(const Scene& scene);

class MaterialTable {
 public:
  // The scene's materials with `overrides` applied in order. Throws lgh::Error(Invalid) naming
  // /materials/<i>/... for a match the scene lacks or parameters that do not apply.
  MaterialTable(const Scene& scene, const std::vector<MaterialOverride>& overrides);

  // Material `index` of the scene; -1 (primitives without a material) and anything out of range
  // give the default material.
  const Material& at(int index) const;
  std::size_t size() const { return materials_.size(); }
  // One per scene material, in the scene's order.
  const std::vector<Material>& materials() const { return materials_; }

 private:
  std::vector<Material> materials_;
  Material default_;
};

}  // namespace lgh
