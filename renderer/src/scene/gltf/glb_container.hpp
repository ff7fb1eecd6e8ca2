// The GLB container (glTF 2.0 "Binary glTF Layout"): a 12-byte header, a JSON chunk, then an
// optional BIN chunk. Checked here, strictly, before tinygltf sees the bytes: tinygltf 2.7 reads
// the BIN chunk's payload from 8 bytes further than the range it checks against the total length,
// so a BIN chunk that claims to reach the end reads past the asset.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "scene/gltf/load_context.hpp"

namespace lgh::gltf {

// Whether the bytes start with the GLB magic "glTF" (the format is told by the content).
bool hasGlbMagic(const std::vector<std::uint8_t>& bytes);

struct GlbChunks {
  std::string_view json;
  std::size_t binOffset = 0;  // the BIN chunk's payload (binBytes 0: no BIN chunk)
  std::size_t binBytes = 0;
  // Chunks of unknown types after those two, which the specification says to ignore (tinygltf
  // refuses them; rebuiltGlb makes the copy it gets).
  std::vector<std::uint32_t> unknownChunkTypes;
};

// Throws lgh::Error(Invalid) naming what is wrong: version other than 2, a total length that is
// not the asset's size, chunk lengths past the end or not a multiple of 4, a first chunk that is
// not JSON, a BIN chunk that is not the second.
GlbChunks readGlbContainer(const std::vector<std::uint8_t>& bytes, const LoadContext& ctx);

// The GLB with `json` as its JSON chunk (padded with spaces), its BIN chunk if any and no other
// chunks, and its total length to match.
std::vector<std::uint8_t> rebuiltGlb(const std::vector<std::uint8_t>& bytes,
                                     const GlbChunks& chunks, std::string_view json);

}  // namespace lgh::gltf
