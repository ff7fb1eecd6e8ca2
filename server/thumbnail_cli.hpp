// lgh-render's thumbnailer form: a model file in, a PNG out, no request JSON.
//   lgh-render MODEL.glb|MODEL.gltf -o OUT.png [--size 256|WxH] [--view iso|front|side|top|X,Y,Z]
//              [--transparent]
// The model's folder becomes the asset root, so a .gltf finds its buffers and images beside it,
// and the camera is the auto camera (the whole model framed) looking from the view's direction.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace lgh::cli {

struct ImageSize {
  int width = 0;
  int height = 0;
};

// "256" (square) or "320x240"; nullopt when it is neither, or a side is not 1..16384.
std::optional<ImageSize> parseImageSize(const std::string& text);

// From the scene's centre towards the camera: "iso" (1,1,1), "front" (0,0,1: glTF's front faces
// +Z), "side" (1,0,0), "top" (0,1,0), or three numbers "X,Y,Z" not all zero; nullopt otherwise.
std::optional<std::array<float, 3>> parseViewDirection(const std::string& text);

// Whether the positional argument names a model rather than a request file.
bool isModelFile(const std::string& path);

// The render request (proto/render-request.schema.json) of a thumbnail of `modelPath`: the model
// as the scene's asset, relative to modelAssetRoot().
nlohmann::json modelRequest(const std::string& modelPath, ImageSize size,
                            const std::array<float, 3>& viewDirection, bool transparent);

// The model's folder, the asset root of its render.
std::string modelAssetRoot(const std::string& modelPath);

}  // namespace lgh::cli
