// WebP texture images (EXT_texture_webp), through libwebp. The image I/O backends know PNG and
// JPEG; WebP is a glTF concern, so it is decoded here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "lgh/image.hpp"
#include "scene/gltf/load_context.hpp"

namespace lgh::gltf {

bool isWebp(const std::uint8_t* bytes, std::size_t size);

// Width and height from the WebP header, without decoding; nullopt when it does not parse.
std::optional<std::pair<std::uint32_t, std::uint32_t>> webpSize(const std::uint8_t* bytes,
                                                                std::size_t size);

// RGBA8; lgh::Error(Invalid) naming `what` when the stream does not decode.
Image8 decodeWebp(const LoadContext& ctx, const std::uint8_t* bytes, std::size_t size,
                  const std::string& what);

}  // namespace lgh::gltf
