#include "scene/gltf/glb_container.hpp"

#include <fmt/format.h>

namespace lgh::gltf {
namespace {

constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   // "BIN\0"
constexpr std::size_t kHeaderBytes = 12;
constexpr std::size_t kChunkHeaderBytes = 8;

std::uint32_t readLittleEndian32(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8U) |
         (static_cast<std::uint32_t>(bytes[2]) << 16U) |
         (static_cast<std::uint32_t>(bytes[3]) << 24U);
}

struct Chunk {
  std::size_t payload = 0;  // offset of the payload
  std::size_t length = 0;
  std::uint32_t type = 0;
};

// The chunk whose header starts at `offset`; its payload must lie inside the asset.
Chunk readChunk(const std::vector<std::uint8_t>& bytes, std::size_t offset, const char* which,
                const LoadContext& ctx) {
  if (bytes.size() - offset < kChunkHeaderBytes) {
    invalid(ctx,
            fmt::format("invalid GLB: the {} chunk's header at byte {} is cut off", which, offset));
  }
  Chunk chunk{offset + kChunkHeaderBytes, readLittleEndian32(bytes.data() + offset),
              readLittleEndian32(bytes.data() + offset + 4)};
  if (chunk.length > bytes.size() - chunk.payload) {
    invalid(ctx, fmt::format("invalid GLB: the {} chunk at byte {} claims {} bytes, {} are left",
                             which, offset, chunk.length, bytes.size() - chunk.payload));
  }
  if (chunk.length % 4 != 0) {
    invalid(ctx, fmt::format("invalid GLB: the {} chunk's length {} is not a multiple of 4", which,
                             chunk.length));
  }
  return chunk;
}

}  // namespace

bool hasGlbMagic(const std::vector<std::uint8_t>& bytes) {
  return bytes.size() >= 4 && readLittleEndian32(bytes.data()) == kMagic;
}

GlbChunks readGlbContainer(const std::vector<std::uint8_t>& bytes, const LoadContext& ctx) {
  if (bytes.size() < kHeaderBytes) {
    invalid(ctx,
            fmt::format("invalid GLB: {} bytes, shorter than the 12-byte header", bytes.size()));
  }
  const std::uint32_t version = readLittleEndian32(bytes.data() + 4);
  if (version != 2) invalid(ctx, fmt::format("GLB version {} is not supported (2 only)", version));
  const std::uint32_t length = readLittleEndian32(bytes.data() + 8);
  if (length != bytes.size()) {
    invalid(ctx, fmt::format("invalid GLB: the header says {} bytes, the asset has {}", length,
                             bytes.size()));
  }
  const Chunk json = readChunk(bytes, kHeaderBytes, "first (JSON)", ctx);
  if (json.type != kJsonChunk) {
    invalid(ctx,
            fmt::format("invalid GLB: the first chunk has type 0x{:08x}, not JSON", json.type));
  }
  if (json.length == 0) invalid(ctx, "invalid GLB: the JSON chunk is empty");
  GlbChunks chunks;
  chunks.json =
      std::string_view(reinterpret_cast<const char*>(bytes.data() + json.payload), json.length);
  for (std::size_t next = json.payload + json.length; next < bytes.size();) {
    const bool second = next == json.payload + json.length;
    const Chunk chunk = readChunk(bytes, next, second ? "second" : "a further", ctx);
    if (chunk.type == kBinChunk) {
      if (!second) {
        invalid(ctx,
                fmt::format("invalid GLB: a BIN chunk at byte {} is not the second chunk", next));
      }
      chunks.binOffset = chunk.payload;
      chunks.binBytes = chunk.length;
    } else if (chunk.type == kJsonChunk) {
      invalid(ctx, fmt::format("invalid GLB: a second JSON chunk at byte {}", next));
    } else {
      chunks.unknownChunkTypes.push_back(chunk.type);
    }
    next = chunk.payload + chunk.length;
  }
  return chunks;
}

std::vector<std::uint8_t> rebuiltGlb(const std::vector<std::uint8_t>& bytes,
                                     const GlbChunks& chunks, std::string_view json) {
  std::vector<std::uint8_t> glb(bytes.begin(), bytes.begin() + kHeaderBytes);
  const auto put32 = [&glb](std::size_t value) {
    for (unsigned i = 0; i < 4; ++i) glb.push_back(static_cast<std::uint8_t>(value >> (8U * i)));
  };
  const std::size_t padding = (4 - json.size() % 4) % 4;  // spaces, as the format asks
  put32(json.size() + padding);
  put32(kJsonChunk);
  glb.insert(glb.end(), json.begin(), json.end());
  glb.insert(glb.end(), padding, static_cast<std::uint8_t>(' '));
  if (chunks.binBytes > 0) {
    const auto binHeader = static_cast<std::ptrdiff_t>(chunks.binOffset - kChunkHeaderBytes);
    glb.insert(glb.end(), bytes.begin() + binHeader,
               bytes.begin() + static_cast<std::ptrdiff_t>(chunks.binOffset + chunks.binBytes));
  }
  const std::size_t length = glb.size();
  for (unsigned i = 0; i < 4; ++i) glb[8 + i] = static_cast<std::uint8_t>(length >> (8U * i));
  return glb;
}

}  // namespace lgh::gltf
