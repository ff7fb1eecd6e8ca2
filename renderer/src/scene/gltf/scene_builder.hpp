// Nodes, lights, cameras: a parsed glTF model -> lgh::Scene. Walks the default scene's node
// hierarchy (refusing cycles, hierarchies deeper than 64 and node DAGs that expand too far),
// converts each mesh on first use and each material once, keeps the drawn triangles within
// limits.maxTriangles, and places the cameras and KHR_lights_punctual lights it meets. Skins and
// morph targets are applied at the bind pose or at ctx.options.animation.
#pragma once

#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"
#include "scene/scene.hpp"

namespace lgh::gltf {

// The Scene, with ctx.warnings moved into Scene::warnings. Throws lgh::Error when the model
// breaks a rule (see gltf_loader.hpp); a scene that draws nothing is empty, with a warning.
Scene buildScene(const tinygltf::Model& model, LoadContext& ctx);

}  // namespace lgh::gltf
