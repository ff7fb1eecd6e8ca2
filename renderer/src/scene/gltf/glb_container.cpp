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
  const std::size_t next = json.payload + json.length;
  if (next == bytes.size()) return chunks;
  const Chunk bin = readChunk(bytes, next, "second (BIN)", ctx);
  if (bin.type != kBinChunk) {
    invalid(ctx, fmt::format("invalid GLB: the second chunk has type 0x{:08x}, not BIN", bin.type));
  }
  if (bin.payload + bin.length != bytes.size()) {
    invalid(ctx, fmt::format("invalid GLB: {} bytes follow the BIN chunk",
                             bytes.size() - bin.payload - bin.length));
  }
  chunks.binBytes = bin.length;
  return chunks;
}

}  // namespace lgh::gltf
