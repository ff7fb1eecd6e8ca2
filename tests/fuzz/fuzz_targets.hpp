// The fuzz targets' bodies, one per parser of untrusted input. libfuzzer_entry.cpp turns each into
// a libFuzzer binary (LGH_FUZZ=ON, clang); test_fuzz_regressions.cpp replays the seed corpora and
// every input a fuzzer ever crashed on (tests/fuzz/regressions/<target>/) through the same bodies
// in the normal test suite. A body returns normally for any input: the parsers' answer to bad
// input is an lgh::Error or an ApiError, which the bodies catch; anything else (another
// exception, a crash, a sanitizer report) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace lgh::fuzz {

// lgh::parseRenderRequest on the bytes as request text (JSON, schema, limits, inline GLB).
void renderRequest(const std::uint8_t* data, std::size_t size);

// The glTF loader on a .gltf or .glb held in memory with side files: the input is the model
// followed by side files, each introduced by a line "\n--lgh-fuzz-file:NAME\n" (see
// splitSideFiles); loaded as an upload (loadGltfFromMemory: external buffers and images through
// the sandboxed side-file callbacks, data URIs), again at an animation's pose when the model has
// animations, and as an inline .glb when it is one.
void gltfLoader(const std::uint8_t* data, std::size_t size);

// The daemon's HTTP front as far as it parses: the bytes as one HTTP request, framing checked
// (checkRequestHead), parsed by httplib (request line, headers, Content-Length body, multipart
// parts) and handed to the upload parsing of POST /v1/render (request part, file parts, scene).
void httpUpload(const std::uint8_t* data, std::size_t size);

// lgh::image_io::decodeTextureRgba8 (PNG, JPEG) on the bytes.
void textureDecoder(const std::uint8_t* data, std::size_t size);

// Quiets the libraries' logging (the renderer warns through spdlog).
void setUpQuietLogging();

inline constexpr std::string_view kSideFileMarker = "\n--lgh-fuzz-file:";

}  // namespace lgh::fuzz
