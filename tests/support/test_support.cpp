#include "test_support.hpp"

#include <cstdlib>

namespace lgh::test {

std::filesystem::path dataDir() { return LGH_TEST_DATA_DIR; }

std::filesystem::path outputDir() {
  std::filesystem::path dir = std::filesystem::path(LGH_BUILD_DIR) / "test-output";
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path assimpGltfDir() { return "/usr/share/assimp/models/glTF2"; }

RendererOptions rendererOptions() {
  RendererOptions options;
  if (const char* backend = std::getenv("LGH_BACKEND"); backend != nullptr && *backend != 0) {
    options.backend = parseContextBackend(backend);
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
