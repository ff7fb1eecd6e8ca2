// The typed form of a render request: what the JSON of proto/render-request.schema.json turns
// into after validation. Passes and the scene code take these structs, never JSON.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/enum_names.hpp"
#include "lgh/error.hpp"
#include "lgh/material_settings.hpp"

namespace lgh {

enum class LightType { Directional, Point, Spot };
template <>
struct EnumNames<LightType> {
  static constexpr std::array<EnumName<LightType>, 3> names{{
      {"point", LightType::Point},
      {"spot", LightType::Spot},
      {"directional", LightType::Directional},
  }};
};

// A light given in the request (beside the ones of the glTF asset). Units follow
// KHR_lights_punctual: point/spot intensity in candela, directional in lux.
struct LightDesc {
  LightType type = LightType::Point;
  std::array<float, 3> position{0, 0, 0};
  std::array<float, 3> direction{0, -1, 0};  // where the light points (directional, spot)
  std::array<float, 3> color{1, 1, 1};
  float intensity = 1.0F;
  // The lecture's attenuation 1 / (kc + kl*d + kq*d^2); glTF lights default to inverse square.
  std::array<float, 3> attenuation{0, 0, 1};
  float range = 0.0F;  // 0: unlimited
  float innerConeAngle = 0.0F;
  float outerConeAngle = 0.785398F;
  float spotExponent = 0.0F;  // the lecture's spot effect cos^exponent, added to the cone falloff
  // The lecture's per-light colours (linear RGB, times intensity): ambient is added unshadowed to
  // every surface the light reaches; diffuse and specular colour the two lobes (unset: color).
  std::array<float, 3> ambient{0, 0, 0};
  std::optional<std::array<float, 3>> diffuse;
  std::optional<std::array<float, 3>> specular;
  // Soft shadows: the size of the light as its shadow rays see it (0: hard shadows). Point and
  // spot lights: radius in world units; directional lights: angular radius in radians.
  float radius = 0.0F;
  float angularRadius = 0.0F;
};

// The scenes built in code (renderer/src/scene/): the demo room, and the atrium the GI benchmark
// runs on (docs/GI.md).
enum class BuiltinScene { Demo, Atrium };
template <>
struct EnumNames<BuiltinScene> {
  static constexpr std::array<EnumName<BuiltinScene>, 2> names{{
      {"demo", BuiltinScene::Demo},
      {"atrium", BuiltinScene::Atrium},
  }};
};

// Where the scene comes from.
struct SceneSource {
  enum class Kind { Builtin, AssetPath, InlineGlb, UploadedGltf };
  Kind kind = Kind::Builtin;
  BuiltinScene builtin = BuiltinScene::Demo;  // Builtin
  std::string assetPath;                      // relative to the asset root (AssetPath)
  std::vector<std::uint8_t> glbBytes;         // decoded base64 or an uploaded .glb (InlineGlb)
  // An uploaded .gltf (UploadedGltf): its file name and every uploaded file by name, side files
  // (buffers, images) included. Its URIs resolve only among these files.
  std::string gltfFileName;
  std::map<std::string, std::vector<std::uint8_t>> uploadedFiles;
  std::string displayName;  // for logs and thumbnail names
};

// scene.animation: the pose a skinned or morphed asset is drawn in.
struct SceneAnimation {
  int index = 0;      // glTF animation index
  float time = 0.0F;  // seconds, clamped to the animation's range
};

// What the request chooses about the scene beside its source (scene.animation,
// scene.material_variant). Kept apart from SceneSource, which the daemon replaces with uploads.
struct SceneOptions {
  std::optional<SceneAnimation> animation;  // none: the bind pose
  std::string materialVariant;              // KHR_materials_variants name; "": the default
};

struct CameraDesc {
  // Default (no camera in the request): the asset's first camera if it has one, else Auto.
  enum class Kind { Default, LookAt, GltfCamera, Auto };
  Kind kind = Kind::Default;
  std::array<float, 3> position{0, 1, 4};
  std::array<float, 3> target{0, 0, 0};
  std::array<float, 3> up{0, 1, 0};
  float yfovDegrees = 45.0F;
  float znear = 0.0F;  // 0: derived from the scene bounds
  float zfar = 0.0F;   // 0: derived from the scene bounds
  int gltfCameraIndex = 0;
  // Auto framing: the scene bounds seen from this direction (camera looks along -viewDirection).
  std::array<float, 3> viewDirection{1, 0.6F, 1.4F};
  float margin = 1.1F;  // >1 leaves room around the bounds
};
template <>
struct EnumNames<CameraDesc::Kind> {
  static constexpr std::array<EnumName<CameraDesc::Kind>, 4> names{{
      {"look_at", CameraDesc::Kind::LookAt},
      {"gltf", CameraDesc::Kind::GltfCamera},
      {"auto", CameraDesc::Kind::Auto},
      {"default", CameraDesc::Kind::Default},  // not in the schema: the absence of a camera
  }};
};

enum class ToneMap { None, Reinhard, Aces };
template <>
struct EnumNames<ToneMap> {
  static constexpr std::array<EnumName<ToneMap>, 3> names{{
      {"none", ToneMap::None},
      {"reinhard", ToneMap::Reinhard},
      {"aces", ToneMap::Aces},
  }};
};

enum class ImageFormat { Png, ExrHalf, ExrFloat };
// "exr" is the half-float EXR: smaller, and enough for a display-referred linear image.
template <>
struct EnumNames<ImageFormat> {
  static constexpr std::array<EnumName<ImageFormat>, 4> names{{
      {"png", ImageFormat::Png},
      {"exr", ImageFormat::ExrHalf},
      {"exr-half", ImageFormat::ExrHalf},
      {"exr-float", ImageFormat::ExrFloat},
  }};
};
// zlib's own default: a balance of size and speed. Level 1 halves the encode time at 1.5x the size.
inline constexpr int kDefaultPngCompression = 6;

struct OutputSettings {
  int width = 640;
  int height = 360;
  ImageFormat format = ImageFormat::Png;
  int pngCompression = kDefaultPngCompression;  // zlib level 0 (none, fastest) .. 9 (smallest)
  ToneMap toneMap = ToneMap::Aces;
  float exposure = 1.0F;
  bool transparentBackground = false;
  std::array<float, 3> background{0.02F, 0.02F, 0.025F};  // linear RGB
};

enum class InterleaveMode { None, Tiles2x2, Tiles4x4 };
template <>
struct EnumNames<InterleaveMode> {
  static constexpr std::array<EnumName<InterleaveMode>, 3> names{{
      {"none", InterleaveMode::None},
      {"2x2", InterleaveMode::Tiles2x2},
      {"4x4", InterleaveMode::Tiles4x4},
  }};
};

enum class LightingPath { Auto, Raster, Compute };
template <>
struct EnumNames<LightingPath> {
  static constexpr std::array<EnumName<LightingPath>, 3> names{{
      {"auto", LightingPath::Auto},
      {"raster", LightingPath::Raster},
      {"compute", LightingPath::Compute},
  }};
};

// How the hierarchy's levels above S1 are built (paper Table 1).
enum class LghBuildMethod { Gather, Scatter };
template <>
struct EnumNames<LghBuildMethod> {
  static constexpr std::array<EnumName<LghBuildMethod>, 2> names{{
      {"gather", LghBuildMethod::Gather},
      {"scatter", LghBuildMethod::Scatter},
  }};
};

// Many-light settings: the LGH built from point lights (VPLs or request lights) and evaluated over
// the G-buffer. Consumed by the LGH build and the lighting passes.
struct LghSettings {
  bool enabled = false;
  int vplCount = 0;  // random VPLs on the scene's surfaces (seeded); 0: none
  std::uint32_t seed = 1;
  float vplIntensity = 1.0F;  // total flux scale of the generated VPLs
  float alpha = 1.0F;
  int levels = 0;  // 0: auto (largest L with |S1| < N/2)
  using Method = LghBuildMethod;
  Method method = Method::Gather;
  InterleaveMode interleave = InterleaveMode::None;
  LightingPath path = LightingPath::Auto;
  int shadowSamples = 4;  // k, 1..8
  // Jitter of the shadow samples' positions, 0..1 of the paper's (a box with the grid light's
  // positional variance), folded to the receiver's side; 0: rays to the illumination centres.
  float shadowJitter = 0.0F;
  bool sampleS1 = false;  // include S1 grid lights in shadow sampling
  bool lockedReservoir = false;
  // Index of a frame in an accumulated sequence: mixed into the shadow samples' random numbers so
  // that averaged frames carry independent noise (0: the seed's own sequence).
  std::uint32_t frame = 0;
};

// Global illumination (docs/GI.md): VPLs left by light paths traced from the frame's lights and
// the scene's emissive triangles, one at each diffuse hit, lighting the frame through the LGH.
struct GiSettings {
  bool enabled = false;
  int bounces = 3;        // diffuse bounces of a light path (1..3), a VPL at each
  int vplCount = 100000;  // VPL slots: paths x (bounces, + 1 where emissive triangles emit)
  std::uint32_t seed = 1;
};

// Shadows by ray tracing on the Vulkan side (docs/SHADOWS.md).
enum class ShadowMode { Auto, On, Off };
template <>
struct EnumNames<ShadowMode> {
  static constexpr std::array<EnumName<ShadowMode>, 3> names{{
      {"auto", ShadowMode::Auto},  // shadowed where the machine can trace rays, else a warning
      {"on", ShadowMode::On},      // shadowed, or the request fails (503)
      {"off", ShadowMode::Off},
  }};
};

enum class ShadowTracing { Auto, RayQuery, Pipeline };
template <>
struct EnumNames<ShadowTracing> {
  static constexpr std::array<EnumName<ShadowTracing>, 3> names{{
      {"auto", ShadowTracing::Auto},
      {"ray-query", ShadowTracing::RayQuery},
      {"pipeline", ShadowTracing::Pipeline},
  }};
};

struct ShadowSettings {
  ShadowMode mode = ShadowMode::Auto;
  ShadowTracing tracing = ShadowTracing::Auto;  // ray query where the device has it
  int lightSamples = 1;      // shadow rays per direct light and pixel (soft shadows: more)
  int filterIterations = 4;  // a-trous passes over the LGH shadow ratio (0: unfiltered)
};

enum class PointShape { Square, Disk };
template <>
struct EnumNames<PointShape> {
  static constexpr std::array<EnumName<PointShape>, 2> names{{
      {"square", PointShape::Square},
      {"disk", PointShape::Disk},
  }};
};

// How glTF POINTS and LINES primitives are drawn (settings.primitives).
struct PrimitiveSettings {
  float pointSize = 4.0F;  // pixels across
  PointShape pointShape = PointShape::Disk;
  float lineWidth = 1.5F;  // pixels
};

// settings.texture_compression: textures kept as uploaded, or block-compressed on upload (BC1/BC3
// colour, BC4 single channel, BC5 normal maps). Precompressed DDS textures stay compressed either
// way.
enum class TextureCompression { None, Bc };
template <>
struct EnumNames<TextureCompression> {
  static constexpr std::array<EnumName<TextureCompression>, 2> names{{
      {"none", TextureCompression::None},
      {"bc", TextureCompression::Bc},
  }};
};

struct RenderSettings {
  float ambient = 0.03F;  // constant ambient term (linear RGB intensity, grey)
  TextureCompression textureCompression = TextureCompression::None;
  // Render assets whose required glTF extensions this renderer lacks, with a warning (else 422).
  bool ignoreUnsupportedExtensions = false;
  // Draw the opaque surfaces' depth first, then the G-buffer once per pixel (docs/LIGHTING.md).
  bool depthPrepass = false;
  PrimitiveSettings primitives;
  ShadowSettings shadows;
  LghSettings lgh;
  GiSettings gi;  // enabled: the LGH's VPLs come from light paths (lgh.enabled is set too)
};

struct RenderRequest {
  SceneSource scene;
  SceneOptions sceneOptions;
  std::vector<LightDesc> lights;      // extra lights beside the asset's
  bool useDemoLightsWhenNone = true;  // an asset with no light gets a default key light
  // Material parameters applied over the scene's materials for this frame (docs/MATERIALS.md).
  std::vector<MaterialOverride> materials;
  CameraDesc camera;
  OutputSettings output;
  RenderSettings settings;
};

// Limits a request is checked against (413/422 when exceeded). The daemon configures them.
struct RequestLimits {
  int maxWidth = 8192;
  int maxHeight = 8192;
  std::int64_t maxPixels = 8192LL * 8192LL;
  int maxLights = 4096;
  int maxVpls = 4 * 1024 * 1024;
  std::size_t maxInlineGlbBytes = std::size_t{256} * 1024U * 1024U;
};

// Validates `json` against proto/render-request.schema.json, then against `limits`, and returns
// the typed request. Throws lgh::Error (BadRequest/Invalid/TooLarge) naming the JSON path.
RenderRequest parseRenderRequest(const nlohmann::json& json, const RequestLimits& limits = {});

// Parses untrusted request text (a render request, a thumbnail batch, a multipart request part)
// within the limits every request JSON has: at most 32 levels of arrays and objects and about a
// million values (TooLarge naming the limit and the byte), then as JSON (BadRequest naming the
// byte of a syntax error).
nlohmann::json parseRequestJson(const std::string& text);

// Parses text first (parseRequestJson): malformed JSON is a BadRequest with the byte offset.
RenderRequest parseRenderRequest(const std::string& text, const RequestLimits& limits = {});
// A string literal is text (without this overload it would be ambiguous with the JSON one).
inline RenderRequest parseRenderRequest(const char* text, const RequestLimits& limits = {}) {
  return parseRenderRequest(std::string(text), limits);
}

// The schema documents shipped in proto/, by file name (e.g. "render-request.schema.json").
const std::string& protoDocument(const std::string& fileName);

// Validates `value` against a proto schema (e.g. "thumbnails-request.schema.json"): throws
// lgh::Error naming the JSON path, BadRequest for shape errors, Invalid for range errors.
void validateAgainstProtoSchema(const nlohmann::json& value, const std::string& schemaFile);

}  // namespace lgh
