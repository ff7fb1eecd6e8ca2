#include "thumbnail_cli.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

namespace lgh::cli {
namespace {

constexpr int kMaxSide = 16384;  // the renderer's own limits refuse what the GPU cannot do

std::optional<int> parseSide(const std::string& text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 1 || value > kMaxSide) {
    return std::nullopt;
  }
  return value;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

std::optional<ImageSize> parseImageSize(const std::string& text) {
  const std::size_t x = lowercase(text).find('x');
  if (x == std::string::npos) {
    const std::optional<int> side = parseSide(text);
    if (!side) return std::nullopt;
    return ImageSize{*side, *side};
  }
  const std::optional<int> width = parseSide(text.substr(0, x));
  const std::optional<int> height = parseSide(text.substr(x + 1));
  if (!width || !height) return std::nullopt;
  return ImageSize{*width, *height};
}

std::optional<std::array<float, 3>> parseViewDirection(const std::string& text) {
  static const std::map<std::string, std::array<float, 3>> kNamed = {
      {"iso", {1, 1, 1}}, {"front", {0, 0, 1}}, {"side", {1, 0, 0}}, {"top", {0, 1, 0}}};
  if (const auto it = kNamed.find(lowercase(text)); it != kNamed.end()) return it->second;
  std::array<float, 3> direction{};
  std::size_t start = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) == (comma == std::string::npos)) return std::nullopt;  // exactly two commas
    const std::string part =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    direction[i] = std::strtof(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(direction[i])) {
      return std::nullopt;
    }
    start = comma + 1;
  }
  if (direction == std::array<float, 3>{0, 0, 0}) return std::nullopt;
  return direction;
}

bool isModelFile(const std::string& path) {
  const std::string extension = lowercase(std::filesystem::path(path).extension().string());
  return extension == ".glb" || extension == ".gltf";
}

nlohmann::json modelRequest(const std::string& modelPath, ImageSize size,
                            const std::array<float, 3>& viewDirection, bool transparent) {
  return {
      {"scene", {{"asset", std::filesystem::path(modelPath).filename().string()}}},
      {"camera", {{"type", "auto"}, {"view_direction", viewDirection}}},
      {"output",
       {{"width", size.width}, {"height", size.height}, {"transparent_background", transparent}}}};
}

std::string modelAssetRoot(const std::string& modelPath) {
  const std::filesystem::path model(modelPath);
  return model.has_parent_path() ? model.parent_path().string() : ".";
}

}  // namespace lgh::cli
