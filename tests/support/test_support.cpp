#include "test_support.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

namespace lgh::test {

std::filesystem::path dataDir() { return LGH_TEST_DATA_DIR; }

std::filesystem::path outputDir() {
  std::filesystem::path dir = std::filesystem::path(LGH_BUILD_DIR) / "test-output";
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path assimpGltfDir() { return "/usr/share/assimp/models/glTF2"; }

std::vector<std::uint8_t> makeTriangleGlb(const std::vector<Position>& positions,
                                          const std::vector<std::uint32_t>& indices) {
  Position lo{1e30F, 1e30F, 1e30F};
  Position hi{-1e30F, -1e30F, -1e30F};
  for (const Position& p : positions) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  const std::size_t positionBytes = positions.size() * sizeof(Position);
  const std::size_t indexBytes = indices.size() * sizeof(std::uint32_t);
  std::vector<std::uint8_t> bin(positionBytes + indexBytes);
  std::memcpy(bin.data(), positions.data(), positionBytes);
  std::memcpy(bin.data() + positionBytes, indices.data(), indexBytes);
  const std::string json = fmt::format(
      R"({{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],)"
      R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],)"
      R"("buffers":[{{"byteLength":{}}}],)"
      R"("bufferViews":[{{"buffer":0,"byteLength":{}}},{{"buffer":0,"byteOffset":{},"byteLength":{}}}],)"
      R"("accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3",)"
      R"("min":[{},{},{}],"max":[{},{},{}]}},)"
      R"({{"bufferView":1,"componentType":5125,"count":{},"type":"SCALAR"}}]}})",
      bin.size(), positionBytes, positionBytes, indexBytes, positions.size(), lo[0], lo[1], lo[2],
      hi[0], hi[1], hi[2], indices.size());
  auto padded = [](std::size_t n) { return (n + 3) / 4 * 4; };
  std::string jsonChunk = json;
  jsonChunk.resize(padded(json.size()), ' ');
  bin.resize(padded(bin.size()), 0);
  std::vector<std::uint8_t> glb;
  auto put32 = [&glb](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) glb.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  put32(0x46546C67U);  // "glTF"
  put32(2);
  put32(static_cast<std::uint32_t>(12 + 8 + jsonChunk.size() + 8 + bin.size()));
  put32(static_cast<std::uint32_t>(jsonChunk.size()));
  put32(0x4E4F534AU);  // "JSON"
  glb.insert(glb.end(), jsonChunk.begin(), jsonChunk.end());
  put32(static_cast<std::uint32_t>(bin.size()));
  put32(0x004E4942U);  // "BIN\0"
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

void addSquare(std::vector<Position>& positions, std::vector<std::uint32_t>& indices, float y,
               float halfSize) {
  const auto base = static_cast<std::uint32_t>(positions.size());
  const float h = halfSize;
  // Counter-clockwise seen from above (+y).
  positions.insert(positions.end(), {{-h, y, h}, {h, y, h}, {h, y, -h}, {-h, y, -h}});
  for (std::uint32_t i : {0U, 1U, 2U, 0U, 2U, 3U}) indices.push_back(base + i);
}

RendererOptions rendererOptions() {
  RendererOptions options;
  if (const char* backend = std::getenv("LGH_BACKEND"); backend != nullptr && *backend != 0) {
    options.backend = parseContextBackend(backend);
  }
  // Upload staging is off on a software rasterizer unless asked for: scripts/run-tests asks for
  // it in one pass, so that the suite runs the GPU's default upload path too.
  if (const char* staging = std::getenv("LGH_UPLOAD_STAGING_MB");
      staging != nullptr && *staging != 0) {
    options.uploadStagingBytes = std::stoll(staging) << 20;
  }
  return options;
}

}  // namespace lgh::test

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

namespace lgh::test {

ImageDifference compareImages(const Image8& actual, const Image8& expected, int threshold) {
  ImageDifference difference;
  if (actual.width != expected.width || actual.height != expected.height ||
      actual.channels != expected.channels) {
    difference.meanAbsoluteError = 255.0;
    difference.fractionOverThreshold = 1.0;
    difference.maxError = 255;
    return difference;
  }
  const size_t pixels = static_cast<size_t>(actual.width) * actual.height;
  const int channels = actual.channels;
  double sum = 0.0;
  size_t over = 0;
  for (size_t p = 0; p < pixels; ++p) {
    int pixelMax = 0;
    for (int c = 0; c < channels; ++c) {
      const size_t i = p * channels + c;
      const int error = std::abs(int(actual.pixels[i]) - int(expected.pixels[i]));
      sum += error;
      pixelMax = std::max(pixelMax, error);
    }
    difference.maxError = std::max(difference.maxError, pixelMax);
    if (pixelMax > threshold) ++over;
  }
  difference.meanAbsoluteError = sum / static_cast<double>(pixels * channels);
  difference.fractionOverThreshold = static_cast<double>(over) / static_cast<double>(pixels);
  return difference;
}

namespace {

Image8 differenceImage(const Image8& actual, const Image8& expected) {
  Image8 diff = actual;
  if (actual.pixels.size() != expected.pixels.size()) return diff;
  for (size_t i = 0; i < diff.pixels.size(); ++i) {
    const int error = std::abs(int(actual.pixels[i]) - int(expected.pixels[i]));
    diff.pixels[i] = static_cast<std::uint8_t>(std::min(255, error * 8));
    if (diff.channels == 4 && i % 4 == 3) diff.pixels[i] = 255;
  }
  return diff;
}

Image8 decodedToImage8(const image_io::Decoded& decoded) {
  Image8 image;
  image.width = decoded.width;
  image.height = decoded.height;
  image.channels = decoded.channels;
  image.pixels = decoded.pixels8;
  return image;
}

}  // namespace

std::string checkGolden(const Image8& actual, const std::string& name, double maxMeanError,
                        double maxFraction) {
  const auto goldenPath = dataDir() / "golden" / (name + ".png");
  const char* update = std::getenv("LGH_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    image_io::writeFile(goldenPath, image_io::encodePng(actual));
    return {};
  }
  const auto actualPath = outputDir() / (name + ".actual.png");
  if (!std::filesystem::exists(goldenPath)) {
    image_io::writeFile(actualPath, image_io::encodePng(actual));
    return fmt::format("no baseline {}; wrote {} (set LGH_UPDATE_GOLDEN=1 to accept)",
                       goldenPath.string(), actualPath.string());
  }
  Image8 expected =
      decodedToImage8(image_io::decode(image_io::readFile(goldenPath), goldenPath.string()));
  const ImageDifference difference = compareImages(actual, expected, 16);
  if (difference.meanAbsoluteError <= maxMeanError &&
      difference.fractionOverThreshold <= maxFraction) {
    return {};
  }
  const auto diffPath = outputDir() / (name + ".diff.png");
  image_io::writeFile(actualPath, image_io::encodePng(actual));
  image_io::writeFile(diffPath, image_io::encodePng(differenceImage(actual, expected)));
  return fmt::format(
      "{}: mean abs error {:.3f} (max {:.3f}), pixels off by >16: {:.4f}% (max {:.4f}%), max "
      "error {}; wrote {} and {}",
      name, difference.meanAbsoluteError, maxMeanError, difference.fractionOverThreshold * 100,
      maxFraction * 100, difference.maxError, actualPath.string(), diffPath.string());
}

}  // namespace lgh::test
