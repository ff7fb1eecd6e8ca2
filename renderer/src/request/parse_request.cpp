// parseRenderRequest: JSON -> checks -> the typed RenderRequest. The checks run in the order a
// client should fix things in: numbers no float can hold (422, checked first because the schema
// cannot see them: NaN passes every bound), shape (400), size limits (413), meaning (422). The
// inline GLB is decoded last, once everything else is known good.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lgh/base64.hpp"
#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "request/json_pointer.hpp"
#include "request/json_read.hpp"
#include "request/json_text.hpp"
#include "request/material_parameters.hpp"
#include "request/schema_validation.hpp"

namespace lgh {
namespace {

using json = nlohmann::json;
using Vec3 = std::array<float, 3>;

// --- Nesting and numbers the schema cannot refuse ----------------------------------------------

// JSON text cannot hold NaN or infinity, but a json built in code can; and a finite double like
// 1e300 becomes infinity as the float the renderer uses. It runs before anything recursive sees
// the document (a json built in code, or parsed from a multipart part, has not been measured as
// text), so it walks without recursion, bounds the nesting, and each node keeps only its parent's
// index and its own token: the pointer is built for the offending value alone.
class NumberScan {
 public:
  void run(const json& document) {
    nodes_.push_back({&document, kNoParent, "", 0});
    for (std::size_t next = 0; next < nodes_.size(); ++next) visit(next);
  }

 private:
  static constexpr std::size_t kNoParent = static_cast<std::size_t>(-1);
  struct Node {
    const json* value;
    std::size_t parent;
    std::string token;
    std::size_t depth;  // containers around this value
  };

  void visit(std::size_t index) {
    const json& value = *nodes_[index].value;
    const std::size_t depth = nodes_[index].depth;
    if ((value.is_object() || value.is_array()) && depth >= kRequestJsonLimits.maxDepth) {
      throw Error(ErrorCode::TooLarge,
                  fmt::format("the request JSON nests deeper than the limit of {} levels of "
                              "arrays and objects",
                              kRequestJsonLimits.maxDepth),
                  pointerOf(index));
    }
    if (value.is_number_float()) {
      checkNumber(value.get<double>(), index);
    } else if (value.is_number_unsigned()) {
      checkUnsigned(value.get<std::uint64_t>(), index);
    } else if (value.is_object()) {
      for (const auto& [key, member] : value.items()) {
        nodes_.push_back({&member, index, key, depth + 1});
      }
    } else if (value.is_array()) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        nodes_.push_back({&value[i], index, std::to_string(i), depth + 1});
      }
    }
  }

  void checkNumber(double number, std::size_t index) const {
    if (!std::isfinite(number)) {
      throw Error(ErrorCode::Invalid, fmt::format("must be a finite number, got {}", number),
                  pointerOf(index));
    }
    if (std::fabs(number) > FLT_MAX) {
      throw Error(
          ErrorCode::Invalid,
          fmt::format("must fit a 32-bit float (magnitude at most {}), got {}", FLT_MAX, number),
          pointerOf(index));
    }
  }

  // valijson reads integers as int64: a larger one would wrap around to a negative number and
  // get a confusing message.
  void checkUnsigned(std::uint64_t number, std::size_t index) const {
    constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    if (number > kMax) {
      throw Error(ErrorCode::Invalid, fmt::format("must be at most {}, got {}", kMax, number),
                  pointerOf(index));
    }
  }

  std::string pointerOf(std::size_t index) const {
    std::vector<std::string> tokens;
    for (; nodes_[index].parent != kNoParent; index = nodes_[index].parent) {
      tokens.push_back(nodes_[index].token);
    }
    return joinPointer({tokens.rbegin(), tokens.rend()});
  }

  std::vector<Node> nodes_;
};

void rejectNonFiniteNumbers(const json& document) { NumberScan().run(document); }

// --- Reading validated JSON into the structs (request/json_read.hpp) ---------------------------

using json_read::read;
using json_read::readEnum;

void readVec3(const json& object, const char* key, Vec3& out) {
  if (const auto it = object.find(key); it != object.end()) {
    for (std::size_t i = 0; i < 3; ++i) out[i] = (*it)[i].get<float>();
  }
}

LightDesc readLight(const json& object) {
  LightDesc light;
  readEnum(object, "type", light.type);
  readVec3(object, "position", light.position);
  readVec3(object, "direction", light.direction);
  readVec3(object, "color", light.color);
  read(object, "intensity", light.intensity);
  readVec3(object, "attenuation", light.attenuation);
  read(object, "range", light.range);
  read(object, "inner_cone_angle", light.innerConeAngle);
  read(object, "outer_cone_angle", light.outerConeAngle);
  read(object, "spot_exponent", light.spotExponent);
  readVec3(object, "ambient", light.ambient);
  if (object.contains("diffuse")) readVec3(object, "diffuse", light.diffuse.emplace());
  if (object.contains("specular")) readVec3(object, "specular", light.specular.emplace());
  read(object, "radius", light.radius);
  read(object, "angular_radius", light.angularRadius);
  return light;
}

CameraDesc readCamera(const json& object) {
  CameraDesc camera;
  readEnum(object, "type", camera.kind);
  readVec3(object, "position", camera.position);
  readVec3(object, "target", camera.target);
  readVec3(object, "up", camera.up);
  read(object, "yfov", camera.yfovDegrees);
  read(object, "znear", camera.znear);
  read(object, "zfar", camera.zfar);
  read(object, "index", camera.gltfCameraIndex);
  readVec3(object, "view_direction", camera.viewDirection);
  read(object, "margin", camera.margin);
  return camera;
}

OutputSettings readOutput(const json& object) {
  OutputSettings output;
  read(object, "width", output.width);
  read(object, "height", output.height);
  readEnum(object, "format", output.format);
  read(object, "png_compression", output.pngCompression);
  readEnum(object, "tone_map", output.toneMap);
  read(object, "exposure", output.exposure);
  read(object, "transparent_background", output.transparentBackground);
  readVec3(object, "background", output.background);
  return output;
}

LghSettings readLgh(const json& object) {
  LghSettings lgh;
  read(object, "enabled", lgh.enabled);
  read(object, "vpl_count", lgh.vplCount);
  read(object, "seed", lgh.seed);
  read(object, "vpl_intensity", lgh.vplIntensity);
  read(object, "alpha", lgh.alpha);
  if (const auto levels = object.find("levels"); levels != object.end()) {
    lgh.levels = levels->is_string() ? 0 : levels->get<int>();  // the string is "auto"
  }
  readEnum(object, "method", lgh.method);
  readEnum(object, "interleave", lgh.interleave);
  readEnum(object, "path", lgh.path);
  read(object, "shadow_samples", lgh.shadowSamples);
  read(object, "shadow_jitter", lgh.shadowJitter);
  read(object, "sample_s1", lgh.sampleS1);
  read(object, "locked_reservoir", lgh.lockedReservoir);
  read(object, "frame", lgh.frame);
  return lgh;
}

PrimitiveSettings readPrimitives(const json& object) {
  PrimitiveSettings primitives;
  read(object, "point_size", primitives.pointSize);
  readEnum(object, "point_shape", primitives.pointShape);
  read(object, "line_width", primitives.lineWidth);
  return primitives;
}

GiSettings readGi(const json& object) {
  GiSettings gi;
  read(object, "enabled", gi.enabled);
  read(object, "bounces", gi.bounces);
  read(object, "vpl_count", gi.vplCount);
  read(object, "seed", gi.seed);
  return gi;
}

RenderSettings readSettings(const json& object) {
  RenderSettings settings;
  read(object, "ambient", settings.ambient);
  readEnum(object, "texture_compression", settings.textureCompression);
  read(object, "ignore_unsupported_extensions", settings.ignoreUnsupportedExtensions);
  read(object, "depth_prepass", settings.depthPrepass);
  if (const auto it = object.find("primitives"); it != object.end()) {
    settings.primitives = readPrimitives(*it);
  }
  readEnum(object, "shadows", settings.shadows.mode);
  readEnum(object, "shadow_path", settings.shadows.tracing);
  read(object, "shadow_light_samples", settings.shadows.lightSamples);
  read(object, "shadow_filter_iterations", settings.shadows.filterIterations);
  if (const auto lgh = object.find("lgh"); lgh != object.end()) settings.lgh = readLgh(*lgh);
  if (const auto gi = object.find("gi"); gi != object.end()) settings.gi = readGi(*gi);
  // GI lights the frame through the LGH (checkGiSettings refuses an explicit "enabled": false).
  if (settings.gi.enabled) settings.lgh.enabled = true;
  return settings;
}

SceneOptions readSceneOptions(const json& scene) {
  SceneOptions options;
  if (const auto it = scene.find("animation"); it != scene.end()) {
    SceneAnimation animation;
    read(*it, "index", animation.index);
    read(*it, "time", animation.time);
    options.animation = animation;
  }
  read(scene, "material_variant", options.materialVariant);
  return options;
}

// Everything but the scene source, whose inline GLB is decoded only after the other checks pass.
RenderRequest readRequestWithoutScene(const json& request) {
  RenderRequest result;
  if (const auto lights = request.find("lights"); lights != request.end()) {
    result.lights.reserve(lights->size());
    for (const json& light : *lights) result.lights.push_back(readLight(light));
  }
  read(request, "use_default_lights", result.useDemoLightsWhenNone);
  if (const auto materials = request.find("materials"); materials != request.end()) {
    for (const json& entry : *materials) result.materials.push_back(readMaterialOverride(entry));
  }
  if (const auto it = request.find("camera"); it != request.end()) result.camera = readCamera(*it);
  if (const auto it = request.find("output"); it != request.end()) result.output = readOutput(*it);
  if (const auto it = request.find("settings"); it != request.end()) {
    result.settings = readSettings(*it);
  }
  if (const auto it = request.find("scene"); it != request.end()) {
    result.sceneOptions = readSceneOptions(*it);
  }
  return result;
}

// --- Limits (413) -----------------------------------------------------------------------------

[[noreturn]] void throwTooLarge(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::TooLarge, message, field);
}

void checkLimits(const RenderRequest& request, const RequestLimits& limits) {
  const OutputSettings& output = request.output;
  if (output.width > limits.maxWidth) {
    throwTooLarge("/output/width", fmt::format("must be at most {} on this server, got {}",
                                               limits.maxWidth, output.width));
  }
  if (output.height > limits.maxHeight) {
    throwTooLarge("/output/height", fmt::format("must be at most {} on this server, got {}",
                                                limits.maxHeight, output.height));
  }
  const std::int64_t pixels = std::int64_t{output.width} * output.height;
  if (pixels > limits.maxPixels) {
    throwTooLarge("/output", fmt::format("width * height must be at most {} pixels on this "
                                         "server, got {} x {} = {}",
                                         limits.maxPixels, output.width, output.height, pixels));
  }
  if (request.lights.size() > static_cast<std::size_t>(limits.maxLights)) {
    throwTooLarge("/lights", fmt::format("must have at most {} lights on this server, got {}",
                                         limits.maxLights, request.lights.size()));
  }
  if (request.settings.lgh.vplCount > limits.maxVpls) {
    throwTooLarge("/settings/lgh/vpl_count",
                  fmt::format("must be at most {} on this server, got {}", limits.maxVpls,
                              request.settings.lgh.vplCount));
  }
  if (request.settings.gi.enabled && request.settings.gi.vplCount > limits.maxVpls) {
    throwTooLarge("/settings/gi/vpl_count",
                  fmt::format("must be at most {} on this server, got {}", limits.maxVpls,
                              request.settings.gi.vplCount));
  }
}

// --- Meaning (422) ----------------------------------------------------------------------------

[[noreturn]] void throwInvalid(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::Invalid, message, field);
}

double length(const Vec3& v) {
  // In double: squaring a small float component would underflow to zero.
  return std::sqrt(double{v[0]} * v[0] + double{v[1]} * v[1] + double{v[2]} * v[2]);
}

Vec3 difference(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// The renderer normalizes directions in float; shorter than this they normalize to garbage.
constexpr double kMinDirectionLength = 1e-6;

std::string vecText(const Vec3& v) { return fmt::format("[{}, {}, {}]", v[0], v[1], v[2]); }

void checkDirection(const Vec3& direction, const std::string& field) {
  if (length(direction) < kMinDirectionLength) {
    throwInvalid(field, fmt::format("must not be zero (length at least {}), got {}",
                                    kMinDirectionLength, vecText(direction)));
  }
}

// Sine of the angle between two non-zero vectors.
double sineBetween(const Vec3& a, const Vec3& b) {
  const Vec3 cross{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return length(cross) / (length(a) * length(b));
}

void checkLight(const LightDesc& light, const std::string& pointer) {
  const bool hasDirection = light.type != LightType::Point;
  if (hasDirection) checkDirection(light.direction, pointer + "/direction");
  if (light.attenuation == Vec3{0, 0, 0}) {
    throwInvalid(pointer + "/attenuation",
                 "must not be all zero: 1 / (kc + kl*d + kq*d^2) would divide by zero");
  }
  if (light.innerConeAngle > light.outerConeAngle) {
    throwInvalid(pointer + "/inner_cone_angle",
                 fmt::format("must be at most outer_cone_angle ({}), got {}", light.outerConeAngle,
                             light.innerConeAngle));
  }
}

// Below this sine (about 0.006 degrees) up and the view direction give no usable camera frame.
constexpr double kMinUpSine = 1e-4;

void checkLookAtCamera(const CameraDesc& camera) {
  const Vec3 view = difference(camera.target, camera.position);
  const double scale = std::max({1.0, length(camera.position), length(camera.target)});
  if (length(view) < kMinDirectionLength * scale) {
    throwInvalid("/camera/target",
                 fmt::format("must differ from position, both are {}", vecText(camera.target)));
  }
  checkDirection(camera.up, "/camera/up");
  if (sineBetween(camera.up, view) < kMinUpSine) {
    throwInvalid("/camera/up",
                 fmt::format("must not be parallel to the view direction target - position = {}",
                             vecText(view)));
  }
  // 0 means "derive from the scene bounds", so only two explicit planes can contradict.
  if (camera.znear > 0 && camera.zfar > 0 && camera.znear >= camera.zfar) {
    throwInvalid("/camera/zfar",
                 fmt::format("must be greater than znear ({}), got {}", camera.znear, camera.zfar));
  }
}

void checkCamera(const CameraDesc& camera) {
  if (camera.kind == CameraDesc::Kind::LookAt) checkLookAtCamera(camera);
  if (camera.kind == CameraDesc::Kind::Auto) {
    checkDirection(camera.viewDirection, "/camera/view_direction");
  }
}

// With settings.gi the VPLs come from light paths: the random-surface VPLs of settings.lgh (a
// benchmark mode) and an LGH switched off contradict it.
void checkGiSettings(const json& request) {
  const auto settings = request.find("settings");
  if (settings == request.end()) return;
  const auto gi = settings->find("gi");
  if (gi == settings->end() || !gi->value("enabled", false)) return;
  const auto lgh = settings->find("lgh");
  if (lgh == settings->end()) return;
  if (lgh->contains("vpl_count")) {
    throwInvalid("/settings/lgh/vpl_count",
                 "random surface VPLs cannot be combined with settings.gi, whose VPLs come from "
                 "light paths: leave vpl_count out (settings.gi.vpl_count sets their number)");
  }
  if (!lgh->value("enabled", true)) {
    throwInvalid("/settings/lgh/enabled",
                 "settings.gi lights the frame through the LGH: it cannot be switched off");
  }
}

void checkMeaning(const RenderRequest& request, const json& document) {
  for (std::size_t i = 0; i < request.lights.size(); ++i) {
    checkLight(request.lights[i], fmt::format("/lights/{}", i));
  }
  checkCamera(request.camera);
  checkGiSettings(document);
}

// --- Scene ------------------------------------------------------------------------------------

// Exactly one source in scene: the schema says it with oneOf, whose failure a validator can only
// report as "no branch matched"; this says it in words, before the schema runs.
void checkSceneSourceCount(const json& request) {
  const auto it = request.find("scene");
  if (it == request.end() || !it->is_object()) return;  // the schema reports other types
  std::size_t sources = 0;
  for (const char* key : {"asset", "builtin", "demo", "glb_base64"}) {
    sources += it->contains(key) ? 1 : 0;
  }
  if (sources != 1) {
    throw Error(ErrorCode::BadRequest,
                fmt::format("must have exactly one of the properties asset, builtin, demo or "
                            "glb_base64, got {}",
                            sources),
                "/scene");
  }
}

std::string fileNameOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

SceneSource readAssetScene(const std::string& path) {
  // The scene code resolves and sandboxes the path; a NUL would cut it short in C APIs there.
  if (path.find('\0') != std::string::npos) {
    throw Error(ErrorCode::BadRequest, "must not contain NUL characters", "/scene/asset");
  }
  SceneSource scene;
  scene.kind = SceneSource::Kind::AssetPath;
  scene.assetPath = path;
  scene.displayName = fileNameOf(path);
  return scene;
}

std::string base64ErrorText(const std::string& text, const base64::DecodeError& error) {
  using Reason = base64::DecodeError::Reason;
  switch (error.reason) {
    case Reason::Length:
      return fmt::format("is not valid base64: length {} is not a multiple of 4", text.size());
    case Reason::PaddingBits:
      return fmt::format("is not valid base64: non-zero padding bits in '{}' at offset {}",
                         text[error.offset], error.offset);
    case Reason::Character:
      break;
  }
  const auto byte = static_cast<unsigned char>(text[error.offset]);
  if (byte >= 0x20 && byte < 0x7F) {
    return fmt::format("is not valid base64: unexpected '{}' at offset {}", text[error.offset],
                       error.offset);
  }
  return fmt::format("is not valid base64: unexpected byte 0x{:02x} at offset {}", byte,
                     error.offset);
}

SceneSource readInlineGlbScene(const std::string& text, const RequestLimits& limits) {
  constexpr const char* kField = "/scene/glb_base64";
  const std::optional<std::size_t> size = base64::decodedSize(text);
  if (size && *size > limits.maxInlineGlbBytes) {
    throw Error(ErrorCode::TooLarge,
                fmt::format("decodes to {} bytes, over this server's limit of {} bytes", *size,
                            limits.maxInlineGlbBytes),
                kField);
  }
  auto decoded = base64::decode(text);
  if (const auto* error = std::get_if<base64::DecodeError>(&decoded)) {
    throw Error(ErrorCode::BadRequest, base64ErrorText(text, *error), kField);
  }
  SceneSource scene;
  scene.kind = SceneSource::Kind::InlineGlb;
  scene.glbBytes = std::move(std::get<std::vector<std::uint8_t>>(decoded));
  scene.displayName = "inline.glb";
  return scene;
}

// The demo keeps the default-constructed SceneSource (empty displayName), so that {} parses to
// exactly RenderRequest{}.
SceneSource readScene(const json& request, const RequestLimits& limits) {
  const auto it = request.find("scene");
  if (it == request.end() || it->contains("demo")) return {};
  if (const auto builtin = it->find("builtin"); builtin != it->end()) {
    SceneSource scene;
    readEnum(*it, "builtin", scene.builtin);
    if (scene.builtin != BuiltinScene::Demo) scene.displayName = builtin->get<std::string>();
    return scene;
  }
  if (const auto asset = it->find("asset"); asset != it->end()) {
    return readAssetScene(asset->get<std::string>());
  }
  return readInlineGlbScene(it->at("glb_base64").get_ref<const std::string&>(), limits);
}

}  // namespace

RenderRequest parseRenderRequest(const json& request, const RequestLimits& limits) {
  if (!request.is_object()) {
    throw Error(ErrorCode::BadRequest,
                fmt::format("the request must be a JSON object, got {}", request.type_name()), "/");
  }
  rejectNonFiniteNumbers(request);
  checkSceneSourceCount(request);
  validateRequestSchema(request);
  RenderRequest result = readRequestWithoutScene(request);
  checkLimits(result, limits);
  checkMeaning(result, request);
  result.scene = readScene(request, limits);
  return result;
}

RenderRequest parseRenderRequest(const std::string& text, const RequestLimits& limits) {
  return parseRenderRequest(parseRequestJson(text), limits);
}

}  // namespace lgh
