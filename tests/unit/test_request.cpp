// The wire contract: proto/*.schema.json and parseRenderRequest. Every kind of bad field must be
// refused with its JSON Pointer and the right status; good requests must become the right structs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "lgh/timing.hpp"
#include "request/embedded_proto.hpp"
#include "request/schema_bundle.hpp"
#include "request/valijson_include.hpp"

namespace lgh {
namespace {

using json = nlohmann::json;

// --- Helpers -----------------------------------------------------------------------------------

// Every field of a RenderRequest as JSON, so that two requests compare with a readable diff.
json describe(const LightDesc& light) {
  return {{"type", static_cast<int>(light.type)},
          {"position", light.position},
          {"direction", light.direction},
          {"color", light.color},
          {"intensity", light.intensity},
          {"attenuation", light.attenuation},
          {"range", light.range},
          {"inner", light.innerConeAngle},
          {"outer", light.outerConeAngle},
          {"spot_exponent", light.spotExponent}};
}

json describe(const RenderRequest& request) {
  json lights = json::array();
  for (const LightDesc& light : request.lights) lights.push_back(describe(light));
  const CameraDesc& camera = request.camera;
  const OutputSettings& output = request.output;
  const LghSettings& lgh = request.settings.lgh;
  return {
      {"scene",
       {{"kind", static_cast<int>(request.scene.kind)},
        {"builtin", static_cast<int>(request.scene.builtin)},
        {"asset", request.scene.assetPath},
        {"glb", request.scene.glbBytes},
        {"name", request.scene.displayName}}},
      {"lights", lights},
      {"use_default_lights", request.useDemoLightsWhenNone},
      {"camera",
       {{"kind", static_cast<int>(camera.kind)},
        {"position", camera.position},
        {"target", camera.target},
        {"up", camera.up},
        {"yfov", camera.yfovDegrees},
        {"znear", camera.znear},
        {"zfar", camera.zfar},
        {"index", camera.gltfCameraIndex},
        {"view_direction", camera.viewDirection},
        {"margin", camera.margin}}},
      {"output",
       {{"width", output.width},
        {"height", output.height},
        {"format", static_cast<int>(output.format)},
        {"tone_map", static_cast<int>(output.toneMap)},
        {"exposure", output.exposure},
        {"png_compression", output.pngCompression},
        {"transparent", output.transparentBackground},
        {"background", output.background}}},
      {"settings",
       {{"ambient", request.settings.ambient},
        {"depth_prepass", request.settings.depthPrepass},
        {"lgh",
         {{"enabled", lgh.enabled},
          {"vpl_count", lgh.vplCount},
          {"seed", lgh.seed},
          {"vpl_intensity", lgh.vplIntensity},
          {"alpha", lgh.alpha},
          {"levels", lgh.levels},
          {"method", static_cast<int>(lgh.method)},
          {"interleave", static_cast<int>(lgh.interleave)},
          {"path", static_cast<int>(lgh.path)},
          {"shadow_samples", lgh.shadowSamples},
          {"sample_s1", lgh.sampleS1},
          {"locked_reservoir", lgh.lockedReservoir},
          {"frame", lgh.frame},
          {"shadow_jitter", lgh.shadowJitter}}},
        {"gi",
         {{"enabled", request.settings.gi.enabled},
          {"bounces", request.settings.gi.bounces},
          {"vpl_count", request.settings.gi.vplCount},
          {"seed", request.settings.gi.seed}}}}},
  };
}

RenderRequest parseText(const std::string& text, const RequestLimits& limits = {}) {
  return parseRenderRequest(text, limits);
}

// The error parsing `text` throws; fails the test when it parses.
Error parseError(const std::string& text, const RequestLimits& limits = {}) {
  try {
    parseText(text, limits);
  } catch (const Error& error) {
    return error;
  }
  ADD_FAILURE() << "parsed without an error: " << text;
  return Error(ErrorCode::Internal, "no error");
}

Error parseError(const json& request, const RequestLimits& limits = {}) {
  try {
    parseRenderRequest(request, limits);
  } catch (const Error& error) {
    return error;
  }
  ADD_FAILURE() << "parsed without an error: " << request.dump();
  return Error(ErrorCode::Internal, "no error");
}

// The JSON Schema documents among the proto files (openapi.json is not one).
std::vector<std::string> schemaFileNames() {
  std::vector<std::string> names;
  for (const auto& [name, text] : embedded::protoFiles()) {
    if (name.ends_with(".schema.json")) names.push_back(name);
  }
  return names;
}

// Compiles a bundled schema with valijson; throws what valijson throws.
void compileSchema(const json& bundle, valijson::Schema& schema) {
  valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
  const valijson::adapters::NlohmannJsonAdapter adapter(bundle);
  parser.populateSchema(adapter, schema);
}

std::vector<std::string> validationErrors(const valijson::Schema& schema, const json& document) {
  valijson::Validator validator(valijson::Validator::kStrongTypes);
  valijson::ValidationResults results;
  const valijson::adapters::NlohmannJsonAdapter target(document);
  validator.validate(schema, target, &results);
  std::vector<std::string> errors;
  for (const auto& error : results) {
    std::string context;
    for (const std::string& part : error.context) context += part;
    errors.push_back(context + ": " + error.description);
  }
  return errors;
}

// --- Rejected requests ------------------------------------------------------------------------

struct BadCase {
  const char* name;
  const char* body;
  ErrorCode code;
  const char* field;
};

void PrintTo(const BadCase& badCase, std::ostream* out) { *out << badCase.name; }

class RejectedRequest : public ::testing::TestWithParam<BadCase> {};

TEST_P(RejectedRequest, NamesFieldAndCode) {
  const BadCase& badCase = GetParam();
  const Error error = parseError(std::string(badCase.body));
  EXPECT_EQ(error.field(), badCase.field) << error.what();
  EXPECT_EQ(errorCodeName(error.code()), std::string(errorCodeName(badCase.code))) << error.what();
  EXPECT_FALSE(error.message().empty());
}

constexpr ErrorCode kBad = ErrorCode::BadRequest;
constexpr ErrorCode kInvalid = ErrorCode::Invalid;

const BadCase kBadCases[] = {
    // Not JSON, or not an object.
    {"malformed_json", R"({"output": )", kBad, ""},
    {"trailing_garbage", R"({} x)", kBad, ""},
    {"empty_body", "", kBad, ""},
    {"array_body", "[1, 2]", kBad, "/"},
    {"number_body", "42", kBad, "/"},
    {"null_body", "null", kBad, "/"},
    // Wrong type.
    {"width_string", R"({"output": {"width": "640"}})", kBad, "/output/width"},
    {"width_fraction", R"({"output": {"width": 640.5}})", kBad, "/output/width"},
    {"bool_as_number", R"({"use_default_lights": 1})", kBad, "/use_default_lights"},
    {"position_component", R"({"lights": [{"type": "point", "position": [0, "a", 0]}]})", kBad,
     "/lights/0/position/1"},
    {"lights_not_array", R"({"lights": {"type": "point"}})", kBad, "/lights"},
    {"camera_position_object", R"({"camera": {"type": "look_at", "position": {}}})", kBad,
     "/camera/position"},
    {"levels_bool", R"({"settings": {"lgh": {"levels": true}}})", kBad, "/settings/lgh/levels"},
    {"vec3_too_short", R"({"camera": {"type": "look_at", "target": [0, 1]}})", kBad,
     "/camera/target"},
    {"scene_string", R"({"scene": "demo"})", kBad, "/scene"},
    {"scene_animation_only", R"({"scene": {"animation": {"index": 0}}})", kBad, "/scene"},
    {"animation_index_missing", R"({"scene": {"asset": "a.glb", "animation": {"time": 1}}})", kBad,
     "/scene/animation/index"},
    {"animation_time_negative",
     R"({"scene": {"asset": "a.glb", "animation": {"index": 0, "time": -1}}})", kInvalid,
     "/scene/animation/time"},
    {"material_variant_empty", R"({"scene": {"asset": "a.glb", "material_variant": ""}})", kBad,
     "/scene/material_variant"},
    {"point_size_zero", R"({"settings": {"primitives": {"point_size": 0}}})", kInvalid,
     "/settings/primitives/point_size"},
    {"point_shape_unknown", R"({"settings": {"primitives": {"point_shape": "star"}}})", kBad,
     "/settings/primitives/point_shape"},
    {"line_width_too_wide", R"({"settings": {"primitives": {"line_width": 100}}})", kInvalid,
     "/settings/primitives/line_width"},
    {"ignore_extensions_string", R"({"settings": {"ignore_unsupported_extensions": "yes"}})", kBad,
     "/settings/ignore_unsupported_extensions"},
    {"width_float_out_of_range", R"({"output": {"width": -1e19}})", kBad, "/output/width"},
    // Unknown property.
    {"unknown_top_level", R"({"foo": 1})", kBad, "/foo"},
    {"unknown_in_output", R"({"output": {"widht": 100}})", kBad, "/output/widht"},
    {"unknown_in_lgh", R"({"settings": {"lgh": {"vpls": 100}}})", kBad, "/settings/lgh/vpls"},
    {"camera_property_of_other_type", R"({"camera": {"type": "gltf", "position": [0, 0, 0]}})",
     kBad, "/camera/position"},
    {"unknown_in_third_light",
     R"({"lights": [{"type": "point"}, {"type": "spot"}, {"type": "point", "colour": [1, 1, 1]}]})",
     kBad, "/lights/2/colour"},
    // Missing required.
    {"camera_without_type", R"({"camera": {"yfov": 30}})", kBad, "/camera/type"},
    {"empty_camera", R"({"camera": {}})", kBad, "/camera/type"},
    {"light_without_type", R"({"lights": [{"position": [0, 1, 0]}]})", kBad, "/lights/0/type"},
    // Not one of the enum values.
    {"format", R"({"output": {"format": "jpg"}})", kBad, "/output/format"},
    {"tone_map", R"({"output": {"tone_map": "filmic"}})", kBad, "/output/tone_map"},
    {"camera_type", R"({"camera": {"type": "orbit"}})", kBad, "/camera/type"},
    {"light_type", R"({"lights": [{"type": "area"}]})", kBad, "/lights/0/type"},
    {"interleave", R"({"settings": {"lgh": {"interleave": "3x3"}}})", kBad,
     "/settings/lgh/interleave"},
    {"levels_string", R"({"settings": {"lgh": {"levels": "max"}}})", kBad, "/settings/lgh/levels"},
    // Scene: exactly one key.
    {"scene_empty", R"({"scene": {}})", kBad, "/scene"},
    {"scene_two_keys", R"({"scene": {"demo": true, "asset": "a.glb"}})", kBad, "/scene"},
    {"scene_demo_false", R"({"scene": {"demo": false}})", kBad, "/scene/demo"},
    {"scene_asset_empty", R"({"scene": {"asset": ""}})", kBad, "/scene/asset"},
    {"scene_asset_nul", R"({"scene": {"asset": "models/a\u0000.glb"}})", kBad, "/scene/asset"},
    // Out of range.
    {"width_too_large", R"({"output": {"width": 10000}})", kInvalid, "/output/width"},
    {"height_zero", R"({"output": {"height": 0}})", kInvalid, "/output/height"},
    {"yfov_180", R"({"camera": {"type": "auto", "yfov": 180}})", kInvalid, "/camera/yfov"},
    {"yfov_0", R"({"camera": {"type": "look_at", "yfov": 0}})", kInvalid, "/camera/yfov"},
    {"alpha_0", R"({"settings": {"lgh": {"alpha": 0}}})", kInvalid, "/settings/lgh/alpha"},
    {"alpha_17", R"({"settings": {"lgh": {"alpha": 16.5}}})", kInvalid, "/settings/lgh/alpha"},
    {"shadow_samples_9", R"({"settings": {"lgh": {"shadow_samples": 9}}})", kInvalid,
     "/settings/lgh/shadow_samples"},
    {"shadow_samples_0", R"({"settings": {"lgh": {"shadow_samples": 0}}})", kInvalid,
     "/settings/lgh/shadow_samples"},
    {"levels_17", R"({"settings": {"lgh": {"levels": 17}}})", kInvalid, "/settings/lgh/levels"},
    {"vpl_count_schema_max", R"({"settings": {"lgh": {"vpl_count": 16777217}}})", kInvalid,
     "/settings/lgh/vpl_count"},
    {"seed_negative", R"({"settings": {"lgh": {"seed": -1}}})", kInvalid, "/settings/lgh/seed"},
    {"intensity_negative", R"({"lights": [{"type": "point", "intensity": -1}]})", kInvalid,
     "/lights/0/intensity"},
    {"color_component_negative", R"({"lights": [{"type": "point", "color": [1, -0.5, 0]}]})",
     kInvalid, "/lights/0/color/1"},
    {"attenuation_negative", R"({"lights": [{"type": "point", "attenuation": [1, 0, -1]}]})",
     kInvalid, "/lights/0/attenuation/2"},
    {"exposure_0", R"({"output": {"exposure": 0}})", kInvalid, "/output/exposure"},
    {"png_compression_10", R"({"output": {"png_compression": 10}})", kInvalid,
     "/output/png_compression"},
    {"margin_below_1", R"({"camera": {"type": "auto", "margin": 0.5}})", kInvalid,
     "/camera/margin"},
    {"outer_cone_too_wide", R"({"lights": [{"type": "spot", "outer_cone_angle": 2}]})", kInvalid,
     "/lights/0/outer_cone_angle"},
    // Numbers no float can hold.
    {"overflow_1e999", R"({"camera": {"type": "look_at", "position": [1e999, 0, 0]}})", kInvalid,
     "/camera/position/0"},
    {"overflow_negative", R"({"lights": [{"type": "point", "intensity": -1e999}]})", kInvalid,
     "/lights/0/intensity"},
    {"float_overflow_1e300", R"({"lights": [{"type": "point", "intensity": 1e300}]})", kInvalid,
     "/lights/0/intensity"},
    {"integer_beyond_int64", R"({"camera": {"type": "gltf", "index": 18446744073709551615}})",
     kInvalid, "/camera/index"},
    // Semantic checks.
    {"zero_attenuation", R"({"lights": [{"type": "point", "attenuation": [0, 0, 0]}]})", kInvalid,
     "/lights/0/attenuation"},
    {"zero_spot_direction", R"({"lights": [{"type": "spot", "direction": [0, 0, 0]}]})", kInvalid,
     "/lights/0/direction"},
    {"zero_directional_direction",
     R"({"lights": [{"type": "point"}, {"type": "directional", "direction": [0, 0, 0]}]})",
     kInvalid, "/lights/1/direction"},
    {"inner_above_outer",
     R"({"lights": [{"type": "spot", "inner_cone_angle": 0.6, "outer_cone_angle": 0.5}]})",
     kInvalid, "/lights/0/inner_cone_angle"},
    {"position_equals_target",
     R"({"camera": {"type": "look_at", "position": [1, 2, 3], "target": [1, 2, 3]}})", kInvalid,
     "/camera/target"},
    {"up_parallel",
     R"({"camera": {"type": "look_at", "position": [0, 5, 0], "target": [0, 0, 0]}})", kInvalid,
     "/camera/up"},
    {"up_zero", R"({"camera": {"type": "look_at", "up": [0, 0, 0]}})", kInvalid, "/camera/up"},
    {"znear_not_below_zfar", R"({"camera": {"type": "look_at", "znear": 10, "zfar": 5}})", kInvalid,
     "/camera/zfar"},
    {"zero_view_direction", R"({"camera": {"type": "auto", "view_direction": [0, 0, 0]}})",
     kInvalid, "/camera/view_direction"},
    // Bad base64.
    {"base64_length", R"({"scene": {"glb_base64": "Zm9"}})", kBad, "/scene/glb_base64"},
    {"base64_character", R"({"scene": {"glb_base64": "Zm9!"}})", kBad, "/scene/glb_base64"},
    {"base64_whitespace", R"({"scene": {"glb_base64": "Zm9v\nYmFy"}})", kBad, "/scene/glb_base64"},
    {"base64_url_alphabet", R"({"scene": {"glb_base64": "Zm9-"}})", kBad, "/scene/glb_base64"},
    {"base64_padding_bits", R"({"scene": {"glb_base64": "Zh=="}})", kBad, "/scene/glb_base64"},
    {"base64_inner_padding", R"({"scene": {"glb_base64": "Zg==Zg=="}})", kBad, "/scene/glb_base64"},
};

INSTANTIATE_TEST_SUITE_P(Request, RejectedRequest, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(RequestErrors, MalformedJsonNamesTheByte) {
  const Error error = parseError(std::string(R"({"output": })"));
  EXPECT_EQ(error.code(), ErrorCode::BadRequest);
  EXPECT_EQ(error.field(), "");
  EXPECT_TRUE(error.message().starts_with("malformed JSON at byte 12: ")) << error.message();
}

TEST(RequestErrors, MessagesAreReadable) {
  const std::map<std::string, std::string> expected{
      {R"({"output": {"width": 10000}})", "must be at most 8192, got 10000"},
      {R"({"output": {"width": "640"}})", R"(must be an integer, got "640")"},
      {R"({"camera": {"type": "auto", "yfov": 180}})", "must be less than 180, got 180"},
      {R"({"output": {"exposure": 0}})", "must be greater than 0, got 0"},
      {R"({"camera": {"type": "look_at", "target": [0, 1]}})", "must have exactly 3 items, got 2"},
      {R"({"output": {"format": "jpg"}})",
       R"(must be "png", "exr", "exr-half" or "exr-float", got "jpg")"},
      {R"({"settings": {"lgh": {"levels": "max"}}})", R"(must be "auto", got "max")"},
      {R"({"camera": {"type": "gltf"}, "lights": [{}]})", "is required"},
      {R"({"scene": {"asset": ""}})", "must not be empty"},
      {R"({"lights": [{"type": "point", "intensity": 1e999}]})",
       "must be a finite number, got 1e999 (too large for a double)"},
  };
  for (const auto& [body, message] : expected) {
    EXPECT_EQ(parseError(body).message(), message) << body;
  }
}

TEST(RequestErrors, UnknownPropertyListsTheAllowedOnes) {
  const Error error = parseError(std::string(R"({"camera": {"type": "gltf", "yfov": 30}})"));
  EXPECT_EQ(error.field(), "/camera/yfov");
  EXPECT_EQ(error.message(), "unknown property; allowed here: index, type");
}

TEST(RequestErrors, SceneWithTwoKeysSaysWhichAreAllowed) {
  const Error error = parseError(std::string(R"({"scene": {"demo": true, "asset": "a.glb"}})"));
  EXPECT_EQ(error.message(),
            "must have exactly one of the properties asset, builtin, demo or glb_base64, got 2");
}

TEST(RequestErrors, NonFiniteNumbersInJsonBuiltInCode) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  json request = {{"camera", {{"type", "look_at"}, {"position", {0.0, nan, 0.0}}}}};
  Error error = parseError(request);
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_EQ(error.field(), "/camera/position/1");

  request = {{"output", {{"width", inf}}}};
  error = parseError(request);
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_EQ(error.field(), "/output/width");

  request = {{"settings", {{"ambient", -inf}}}};
  EXPECT_EQ(parseError(request).field(), "/settings/ambient");
}

TEST(RequestErrors, NonObjectJsonValue) {
  const Error error = parseError(json::array({1, 2}));
  EXPECT_EQ(error.code(), ErrorCode::BadRequest);
  EXPECT_EQ(error.field(), "/");
}

TEST(RequestErrors, DeepNestingIsRefusedBeforeParsing) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const Error error = parseError(R"({"junk": )" + deep + "}");
  EXPECT_EQ(error.code(), ErrorCode::TooLarge);
  EXPECT_NE(error.message().find("limit of 32 levels"), std::string::npos) << error.message();
  EXPECT_NE(error.message().find("at byte 40"), std::string::npos) << error.message();  // 33rd [
  // 32 levels are fine as far as nesting goes (the schema then refuses the unknown property).
  const std::string allowed = std::string(31, '[') + std::string(31, ']');
  EXPECT_EQ(parseError(R"({"junk": )" + allowed + "}").code(), ErrorCode::BadRequest);
}

TEST(RequestErrors, DeepNestingOfJsonBuiltInCodeIsRefusedNamingThePointer) {
  nlohmann::json deep = nlohmann::json::array();
  for (int i = 0; i < 40; ++i) deep = nlohmann::json::array({std::move(deep)});
  try {
    parseRenderRequest(nlohmann::json{{"lights", deep}});
    FAIL() << "accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::TooLarge);
    EXPECT_EQ(
        error.field(), "/lights" + [] {
          std::string tail;
          for (int i = 0; i < 31; ++i) tail += "/0";
          return tail;
        }());
  }
}

TEST(RequestErrors, TooManyValuesAreRefusedBeforeParsing) {
  std::string many = "[0";
  for (int i = 0; i < 1'000'000; ++i) many += ",0";
  const Error error = parseError(R"({"junk": )" + many + "]}");
  EXPECT_EQ(error.code(), ErrorCode::TooLarge);
  EXPECT_NE(error.message().find("limit of 1000000 values"), std::string::npos) << error.message();
}

// --- Limits -----------------------------------------------------------------------------------

TEST(RequestLimitsTest, OverLimitsAreTooLarge) {
  RequestLimits limits;
  limits.maxWidth = 1024;
  limits.maxHeight = 512;
  limits.maxPixels = 300'000;
  limits.maxLights = 2;
  limits.maxVpls = 1000;
  limits.maxInlineGlbBytes = 5;

  const std::map<std::string, std::string> expectedField{
      {R"({"output": {"width": 1025}})", "/output/width"},
      {R"({"output": {"height": 513}})", "/output/height"},
      {R"({"output": {"width": 1000, "height": 400}})", "/output"},
      {R"({"lights": [{"type": "point"}, {"type": "point"}, {"type": "point"}]})", "/lights"},
      {R"({"settings": {"lgh": {"vpl_count": 1001}}})", "/settings/lgh/vpl_count"},
      {R"({"scene": {"glb_base64": "Zm9vYmFy"}})", "/scene/glb_base64"},
  };
  for (const auto& [body, field] : expectedField) {
    const Error error = parseError(body, limits);
    EXPECT_EQ(error.code(), ErrorCode::TooLarge) << body << ": " << error.what();
    EXPECT_EQ(error.field(), field) << body;
  }
  // At the limits exactly, everything passes.
  const RenderRequest atLimits = parseText(
      R"({"output": {"width": 600, "height": 500}, "lights": [{"type": "point"}, {"type": "spot"}],
          "settings": {"lgh": {"vpl_count": 1000}}, "scene": {"glb_base64": "Zm9vYg=="}})",
      limits);
  EXPECT_EQ(atLimits.scene.glbBytes.size(), 4U);
}

TEST(RequestLimitsTest, DefaultLimitsAllowTheSchemaMaximum) {
  const RenderRequest request = parseText(R"({"output": {"width": 8192, "height": 8192}})");
  EXPECT_EQ(request.output.width, 8192);
  const Error error = parseError(std::string(R"({"settings": {"lgh": {"vpl_count": 5000000}}})"));
  EXPECT_EQ(error.code(), ErrorCode::TooLarge);
}

// --- Accepted requests ------------------------------------------------------------------------

TEST(RequestParse, SceneOptionsAndPrimitiveSettings) {
  const RenderRequest request = parseText(R"({
    "scene": {"asset": "simple_skin/simple_skin.gltf", "animation": {"index": 1, "time": 2.5},
              "material_variant": "red"},
    "settings": {"ignore_unsupported_extensions": true,
                 "primitives": {"point_size": 8, "point_shape": "square", "line_width": 3}}})");
  EXPECT_EQ(request.scene.kind, SceneSource::Kind::AssetPath);
  ASSERT_TRUE(request.sceneOptions.animation.has_value());
  EXPECT_EQ(request.sceneOptions.animation->index, 1);
  EXPECT_FLOAT_EQ(request.sceneOptions.animation->time, 2.5F);
  EXPECT_EQ(request.sceneOptions.materialVariant, "red");
  EXPECT_TRUE(request.settings.ignoreUnsupportedExtensions);
  EXPECT_FLOAT_EQ(request.settings.primitives.pointSize, 8.0F);
  EXPECT_EQ(request.settings.primitives.pointShape, lgh::PointShape::Square);
  EXPECT_FLOAT_EQ(request.settings.primitives.lineWidth, 3.0F);
  // Without them: the bind pose, the default variant, refusal of unknown required extensions.
  const RenderRequest plain = parseText(R"({"scene": {"asset": "a.glb"}})");
  EXPECT_FALSE(plain.sceneOptions.animation.has_value());
  EXPECT_TRUE(plain.sceneOptions.materialVariant.empty());
  EXPECT_FALSE(plain.settings.ignoreUnsupportedExtensions);
  EXPECT_EQ(plain.settings.primitives.pointShape, lgh::PointShape::Disk);
}

TEST(RequestParse, EmptyObjectIsAllDefaults) {
  EXPECT_EQ(describe(parseText("{}")), describe(RenderRequest{}));
  EXPECT_EQ(describe(parseRenderRequest(json::object())), describe(RenderRequest{}));
}

TEST(RequestParse, FullRequestBecomesTypedValues) {
  const RenderRequest request = parseText(R"({
    "scene": {"asset": "models/sponza/Sponza.gltf"},
    "lights": [
      {"type": "spot", "position": [1, 2, 3], "direction": [0, -1, 0.5], "color": [1, 0.5, 0.25],
       "intensity": 20, "attenuation": [1, 0.5, 0.25], "range": 10, "inner_cone_angle": 0.2,
       "outer_cone_angle": 0.6, "spot_exponent": 8},
      {"type": "directional", "direction": [0, -1, 0]},
      {"type": "point"}
    ],
    "use_default_lights": false,
    "camera": {"type": "look_at", "position": [0, 2, 5], "target": [0, 1, 0], "up": [0, 0, 1],
               "yfov": 60, "znear": 0.1, "zfar": 100},
    "output": {"width": 1920, "height": 1080, "format": "exr-float", "tone_map": "reinhard",
               "exposure": 2.5, "png_compression": 1, "transparent_background": true, "background": [0.1, 0.2, 0.3]},
    "settings": {"ambient": 0.1,
                 "lgh": {"enabled": true, "vpl_count": 100000, "seed": 4294967295,
                         "vpl_intensity": 3, "alpha": 2, "levels": 5, "method": "scatter",
                         "interleave": "4x4", "path": "compute", "shadow_samples": 8,
                         "sample_s1": true, "locked_reservoir": true}}
  })");
  EXPECT_EQ(request.scene.kind, SceneSource::Kind::AssetPath);
  EXPECT_EQ(request.scene.assetPath, "models/sponza/Sponza.gltf");
  EXPECT_EQ(request.scene.displayName, "Sponza.gltf");

  ASSERT_EQ(request.lights.size(), 3U);
  const LightDesc& spot = request.lights[0];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_EQ(spot.position, (std::array<float, 3>{1, 2, 3}));
  EXPECT_EQ(spot.direction, (std::array<float, 3>{0, -1, 0.5F}));
  EXPECT_EQ(spot.color, (std::array<float, 3>{1, 0.5F, 0.25F}));
  EXPECT_FLOAT_EQ(spot.intensity, 20);
  EXPECT_EQ(spot.attenuation, (std::array<float, 3>{1, 0.5F, 0.25F}));
  EXPECT_FLOAT_EQ(spot.range, 10);
  EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.2F);
  EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.6F);
  EXPECT_FLOAT_EQ(spot.spotExponent, 8);
  EXPECT_EQ(request.lights[1].type, LightType::Directional);
  EXPECT_EQ(describe(request.lights[2]), describe(LightDesc{}));
  EXPECT_FALSE(request.useDemoLightsWhenNone);

  const CameraDesc& camera = request.camera;
  EXPECT_EQ(camera.kind, CameraDesc::Kind::LookAt);
  EXPECT_EQ(camera.position, (std::array<float, 3>{0, 2, 5}));
  EXPECT_EQ(camera.target, (std::array<float, 3>{0, 1, 0}));
  EXPECT_EQ(camera.up, (std::array<float, 3>{0, 0, 1}));
  EXPECT_FLOAT_EQ(camera.yfovDegrees, 60);
  EXPECT_FLOAT_EQ(camera.znear, 0.1F);
  EXPECT_FLOAT_EQ(camera.zfar, 100);

  const OutputSettings& output = request.output;
  EXPECT_EQ(output.width, 1920);
  EXPECT_EQ(output.height, 1080);
  EXPECT_EQ(output.format, ImageFormat::ExrFloat);
  EXPECT_EQ(output.toneMap, ToneMap::Reinhard);
  EXPECT_FLOAT_EQ(output.exposure, 2.5F);
  EXPECT_EQ(output.pngCompression, 1);
  EXPECT_TRUE(output.transparentBackground);
  EXPECT_EQ(output.background, (std::array<float, 3>{0.1F, 0.2F, 0.3F}));

  EXPECT_FLOAT_EQ(request.settings.ambient, 0.1F);
  const LghSettings& lgh = request.settings.lgh;
  EXPECT_TRUE(lgh.enabled);
  EXPECT_EQ(lgh.vplCount, 100000);
  EXPECT_EQ(lgh.seed, 4294967295U);
  EXPECT_FLOAT_EQ(lgh.vplIntensity, 3);
  EXPECT_FLOAT_EQ(lgh.alpha, 2);
  EXPECT_EQ(lgh.levels, 5);
  EXPECT_EQ(lgh.method, LghSettings::Method::Scatter);
  EXPECT_EQ(lgh.interleave, InterleaveMode::Tiles4x4);
  EXPECT_EQ(lgh.path, LightingPath::Compute);
  EXPECT_EQ(lgh.shadowSamples, 8);
  EXPECT_TRUE(lgh.sampleS1);
  EXPECT_TRUE(lgh.lockedReservoir);
}

TEST(RequestParse, CameraVariants) {
  RenderRequest request = parseText(R"({"camera": {"type": "gltf", "index": 3}})");
  EXPECT_EQ(request.camera.kind, CameraDesc::Kind::GltfCamera);
  EXPECT_EQ(request.camera.gltfCameraIndex, 3);

  request = parseText(
      R"({"camera": {"type": "auto", "view_direction": [0, 1, 1], "margin": 1.5, "yfov": 30}})");
  EXPECT_EQ(request.camera.kind, CameraDesc::Kind::Auto);
  EXPECT_EQ(request.camera.viewDirection, (std::array<float, 3>{0, 1, 1}));
  EXPECT_FLOAT_EQ(request.camera.margin, 1.5F);
  EXPECT_FLOAT_EQ(request.camera.yfovDegrees, 30);
}

TEST(RequestParse, EnumSpellings) {
  EXPECT_EQ(parseText(R"({"output": {"format": "exr"}})").output.format, ImageFormat::ExrHalf);
  EXPECT_EQ(parseText(R"({"output": {"format": "exr-half"}})").output.format, ImageFormat::ExrHalf);
  EXPECT_EQ(parseText(R"({"output": {"format": "png"}})").output.format, ImageFormat::Png);
  EXPECT_EQ(parseText(R"({"output": {"tone_map": "none"}})").output.toneMap, ToneMap::None);
  EXPECT_EQ(parseText(R"({"settings": {"lgh": {"levels": "auto"}}})").settings.lgh.levels, 0);
  EXPECT_EQ(parseText(R"({"settings": {"lgh": {"interleave": "2x2"}}})").settings.lgh.interleave,
            InterleaveMode::Tiles2x2);
  EXPECT_EQ(parseText(R"({"settings": {"lgh": {"path": "raster"}}})").settings.lgh.path,
            LightingPath::Raster);
}

TEST(RequestParse, SceneSources) {
  RenderRequest request = parseText(R"({"scene": {"demo": true}})");
  EXPECT_EQ(request.scene.kind, SceneSource::Kind::Builtin);
  EXPECT_EQ(request.scene.builtin, BuiltinScene::Demo);

  // "glTF" + version 2 + length 12: a GLB header.
  request = parseText(R"({"scene": {"glb_base64": "Z2xURgIAAAAMAAAA"}})");
  EXPECT_EQ(request.scene.kind, SceneSource::Kind::InlineGlb);
  EXPECT_EQ(request.scene.glbBytes,
            (std::vector<std::uint8_t>{'g', 'l', 'T', 'F', 2, 0, 0, 0, 12, 0, 0, 0}));
  EXPECT_FALSE(request.scene.displayName.empty());
}

TEST(RequestParse, ZeroPlanesAreDerivedNotContradictory) {
  const RenderRequest request =
      parseText(R"({"camera": {"type": "look_at", "znear": 5, "zfar": 0}})");
  EXPECT_FLOAT_EQ(request.camera.znear, 5);
}

// Every "default" the schema states, sent explicitly, must parse to the struct's default.
TEST(RequestParse, SchemaDefaultsMatchStructDefaults) {
  const json bundle = bundleSchema("render-request.schema.json");
  const auto& definitions = bundle.at("$defs");
  const json& lgh = definitions.at("render-settings.schema.json").at("$defs").at("lgh");
  const json& camera = definitions.at("camera.schema.json").at("$defs");

  auto expectDefaults = [](const json& properties, const std::function<json(json)>& wrap,
                           const RenderRequest& expected) {
    for (const auto& [name, schema] : properties.items()) {
      if (!schema.contains("default")) continue;
      const json request = wrap({{name, schema.at("default")}});
      EXPECT_EQ(describe(parseRenderRequest(request)), describe(expected)) << request.dump();
    }
  };
  const RenderRequest defaults;
  expectDefaults(
      bundle.at("properties"), [](json o) { return o; }, defaults);
  expectDefaults(
      bundle.at("$defs").at("output").at("properties"),
      [](json o) {
        return json{{"output", o}};
      },
      defaults);
  expectDefaults(
      definitions.at("render-settings.schema.json").at("properties"),
      [](json o) {
        return json{{"settings", o}};
      },
      defaults);
  expectDefaults(
      lgh.at("properties"),
      [](json o) {
        return json{{"settings", {{"lgh", o}}}};
      },
      defaults);
  expectDefaults(
      definitions.at("render-settings.schema.json").at("$defs").at("gi").at("properties"),
      [](json o) {
        return json{{"settings", {{"gi", o}}}};
      },
      defaults);

  auto withType = [](const char* type) {
    return [type](json o) {
      o["type"] = type;
      return json{{"camera", o}};
    };
  };
  RenderRequest autoCamera;
  autoCamera.camera.kind = CameraDesc::Kind::Auto;
  expectDefaults(camera.at("auto").at("properties"), withType("auto"), autoCamera);
  RenderRequest lookAt;
  lookAt.camera.kind = CameraDesc::Kind::LookAt;
  expectDefaults(camera.at("look_at").at("properties"), withType("look_at"), lookAt);
  RenderRequest gltf;
  gltf.camera.kind = CameraDesc::Kind::GltfCamera;
  expectDefaults(camera.at("gltf").at("properties"), withType("gltf"), gltf);

  RenderRequest oneLight;
  oneLight.lights.emplace_back();
  expectDefaults(
      definitions.at("light.schema.json").at("properties"),
      [](json o) {
        o["type"] = "point";
        return json{{"lights", {o}}};
      },
      oneLight);
}

// --- Errors -----------------------------------------------------------------------------------

// The HTTP status of each code is the daemon's business: tests/daemon/test_api_error.cpp.
TEST(ErrorCodes, Names) {
  const std::vector<std::pair<ErrorCode, std::string>> expected{
      {ErrorCode::BadRequest, "bad_request"},  {ErrorCode::NotFound, "not_found"},
      {ErrorCode::TooLarge, "too_large"},      {ErrorCode::Invalid, "invalid"},
      {ErrorCode::Unavailable, "unavailable"}, {ErrorCode::Timeout, "timeout"},
      {ErrorCode::Internal, "internal"},
  };
  for (const auto& [code, name] : expected) EXPECT_EQ(errorCodeName(code), name);
}

// --- Proto documents --------------------------------------------------------------------------

TEST(ProtoDocuments, AllShippedAndReachable) {
  const std::vector<std::string> expected{
      "camera.schema.json",          "light.schema.json",
      "render-request.schema.json",  "render-response.schema.json",
      "render-settings.schema.json", "scene.schema.json",
      "timings.schema.json",         "thumbnails-request.schema.json",
      "job-request.schema.json",     "job-status.schema.json",
      "benchmark-result.schema.json"};
  const std::vector<std::string> shipped = schemaFileNames();
  for (const std::string& name : expected) {
    EXPECT_FALSE(protoDocument(name).empty()) << name;
    EXPECT_NE(std::find(shipped.begin(), shipped.end(), name), shipped.end()) << name;
  }
}

TEST(ProtoDocuments, UnknownNameIsNotFound) {
  try {
    protoDocument("nope.schema.json");
    FAIL() << "no exception";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::NotFound);
    EXPECT_EQ(error.field(), "nope.schema.json");
  }
}

// The draft-07 meta-schema (http://json-schema.org/draft-07/schema), verbatim.
constexpr const char* kDraft07MetaSchema = R"json({
    "$schema": "http://json-schema.org/draft-07/schema#",
    "$id": "http://json-schema.org/draft-07/schema#",
    "title": "Core schema meta-schema",
    "definitions": {
        "schemaArray": {"type": "array", "minItems": 1, "items": { "$ref": "#" }},
        "nonNegativeInteger": {"type": "integer", "minimum": 0},
        "nonNegativeIntegerDefault0": {
            "allOf": [{ "$ref": "#/definitions/nonNegativeInteger" }, { "default": 0 }]
        },
        "simpleTypes": {
            "enum": ["array", "boolean", "integer", "null", "number", "object", "string"]
        },
        "stringArray": {
            "type": "array", "items": { "type": "string" }, "uniqueItems": true, "default": []
        }
    },
    "type": ["object", "boolean"],
    "properties": {
        "$id": {"type": "string", "format": "uri-reference"},
        "$schema": {"type": "string", "format": "uri"},
        "$ref": {"type": "string", "format": "uri-reference"},
        "$comment": {"type": "string"},
        "title": {"type": "string"},
        "description": {"type": "string"},
        "default": true,
        "readOnly": {"type": "boolean", "default": false},
        "examples": {"type": "array", "items": true},
        "multipleOf": {"type": "number", "exclusiveMinimum": 0},
        "maximum": {"type": "number"},
        "exclusiveMaximum": {"type": "number"},
        "minimum": {"type": "number"},
        "exclusiveMinimum": {"type": "number"},
        "maxLength": { "$ref": "#/definitions/nonNegativeInteger" },
        "minLength": { "$ref": "#/definitions/nonNegativeIntegerDefault0" },
        "pattern": {"type": "string", "format": "regex"},
        "additionalItems": { "$ref": "#" },
        "items": {
            "anyOf": [{ "$ref": "#" }, { "$ref": "#/definitions/schemaArray" }],
            "default": true
        },
        "maxItems": { "$ref": "#/definitions/nonNegativeInteger" },
        "minItems": { "$ref": "#/definitions/nonNegativeIntegerDefault0" },
        "uniqueItems": {"type": "boolean", "default": false},
        "contains": { "$ref": "#" },
        "maxProperties": { "$ref": "#/definitions/nonNegativeInteger" },
        "minProperties": { "$ref": "#/definitions/nonNegativeIntegerDefault0" },
        "required": { "$ref": "#/definitions/stringArray" },
        "additionalProperties": { "$ref": "#" },
        "definitions": {"type": "object", "additionalProperties": { "$ref": "#" }, "default": {}},
        "properties": {"type": "object", "additionalProperties": { "$ref": "#" }, "default": {}},
        "patternProperties": {
            "type": "object",
            "additionalProperties": { "$ref": "#" },
            "propertyNames": { "format": "regex" },
            "default": {}
        },
        "dependencies": {
            "type": "object",
            "additionalProperties": {
                "anyOf": [{ "$ref": "#" }, { "$ref": "#/definitions/stringArray" }]
            }
        },
        "propertyNames": { "$ref": "#" },
        "const": true,
        "enum": {"type": "array", "items": true},
        "type": {
            "anyOf": [
                { "$ref": "#/definitions/simpleTypes" },
                {
                    "type": "array",
                    "items": { "$ref": "#/definitions/simpleTypes" },
                    "minItems": 1,
                    "uniqueItems": true
                }
            ]
        },
        "format": { "type": "string" },
        "contentMediaType": { "type": "string" },
        "contentEncoding": { "type": "string" },
        "if": { "$ref": "#" },
        "then": { "$ref": "#" },
        "else": { "$ref": "#" },
        "allOf": { "$ref": "#/definitions/schemaArray" },
        "anyOf": { "$ref": "#/definitions/schemaArray" },
        "oneOf": { "$ref": "#/definitions/schemaArray" },
        "not": { "$ref": "#" }
    },
    "default": true
})json";

// Keywords of draft 7 that 2020-12 renamed or reshaped: none may appear in a proto schema.
constexpr const char* kDraft07OnlyKeywords[] = {"definitions", "dependencies", "additionalItems"};
// What may stand beside a "$ref": annotations only. 2020-12 applies a $ref's siblings, valijson
// (draft 7) ignores them; with annotations only, both validate alike.
constexpr const char* kRefAnnotations[] = {"$ref",  "description", "default",
                                           "title", "examples",    "$comment"};

void expectFormsBothRead(const json& node, const std::string& path) {
  if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      expectFormsBothRead(node[i], path + "/" + std::to_string(i));
    }
    return;
  }
  if (!node.is_object()) return;
  for (const char* keyword : kDraft07OnlyKeywords) {
    EXPECT_FALSE(node.contains(keyword)) << path << " uses the draft-07 keyword " << keyword;
  }
  if (node.contains("items")) {
    EXPECT_TRUE(node["items"].is_object())
        << path << ": array-form items is prefixItems in 2020-12";
  }
  if (node.contains("$ref")) {
    for (const auto& [key, value] : node.items()) {
      EXPECT_NE(std::find(std::begin(kRefAnnotations), std::end(kRefAnnotations), key),
                std::end(kRefAnnotations))
          << path << ": \"" << key << "\" beside $ref is applied by 2020-12, ignored by valijson";
    }
  }
  for (const auto& [key, value] : node.items()) {
    if (key != "examples" && key != "default" && key != "enum" && key != "const") {
      expectFormsBothRead(value, std::string(path).append("/").append(key));
    }
  }
}

// The files are JSON Schema 2020-12 (the dialect of OpenAPI 3.1) written in forms valijson, a
// draft-07 validator, reads the same way: so the draft-07 meta-schema accepts them too, and they
// compile. tests/contract validates them against the 2020-12 meta-schema itself (ajv).
TEST(ProtoDocuments, EachIsA2020_12SchemaInFormsValijsonReads) {
  const json metaDocument = json::parse(kDraft07MetaSchema);
  valijson::Schema metaSchema;
  compileSchema(metaDocument, metaSchema);
  for (const std::string& name : schemaFileNames()) {
    SCOPED_TRACE(name);
    json document;
    ASSERT_NO_THROW(document = json::parse(protoDocument(name)));
    EXPECT_EQ(document.value("$schema", ""), "https://json-schema.org/draft/2020-12/schema");
    // No $id: relative $refs ("scene.schema.json") resolve against where the file is, proto/ or
    // the daemon's /proto/, as the OpenAPI document's do.
    EXPECT_FALSE(document.contains("$id"));
    expectFormsBothRead(document, name);
    EXPECT_EQ(validationErrors(metaSchema, document), std::vector<std::string>{});

    // Compiles with valijson, its cross-file references resolved from the embedded files.
    json bundle;
    ASSERT_NO_THROW(bundle = bundleSchema(name));
    valijson::Schema schema;
    EXPECT_NO_THROW(compileSchema(bundle, schema));
  }
}

// The conventions of the contract: every property documented, every object closed.
void expectDocumented(const json& schema, const std::string& path) {
  if (!schema.is_object()) return;
  if (schema.value("type", json()) == "object") {
    // A discriminated oneOf closes the object in each of its branches.
    EXPECT_TRUE(schema.contains("additionalProperties") || schema.contains("allOf") ||
                schema.contains("oneOf"))
        << path << " is an object schema without additionalProperties";
  }
  for (const char* key : {"properties", "$defs"}) {
    if (!schema.contains(key)) continue;
    for (const auto& [name, child] : schema[key].items()) {
      if (std::string(key) == "properties") {
        EXPECT_TRUE(child.contains("description") || child.contains("$ref"))
            << path << "/" << key << "/" << name << " has no description";
      }
      std::string childPath = path;
      childPath.append("/").append(key).append("/").append(name);
      expectDocumented(child, childPath);
    }
  }
  for (const char* key : {"items", "additionalProperties", "then", "else"}) {
    if (schema.contains(key)) expectDocumented(schema[key], path + "/" + key);
  }
}

TEST(ProtoDocuments, EveryPropertyDescribedAndEveryObjectClosed) {
  for (const std::string& name : schemaFileNames()) {
    expectDocumented(json::parse(protoDocument(name)), name);
  }
}

// --- Response schema --------------------------------------------------------------------------

json sampleResponse() {
  TimingTable timings;
  timings.add("scene_load", TimingRow::Clock::Cpu, 12.5);
  timings.add("gbuffer", TimingRow::Clock::Gpu, 1.25);
  timings.add("direct_lighting", TimingRow::Clock::Gpu, 0.75);
  return {
      {"image", "iVBORw0KGgo="},
      {"mime", "image/png"},
      {"width", 640},
      {"height", 360},
      {"timings", timings.toJson()},
      {"device",
       {{"context_path", "surfaceless"},
        {"gl_vendor", "Mesa"},
        {"gl_renderer", "llvmpipe (LLVM 15.0.6, 256 bits)"},
        {"gl_version", "4.5 (Core Profile) Mesa 22.3.6"},
        {"glsl_version", "4.50"},
        {"gl_major", 4},
        {"gl_minor", 5},
        {"egl_device_index", -1},
        {"egl_device_count", 0},
        {"software_renderer", true},
        {"image_backend", "oiio"}}},
      {"paths", {{"lighting", "raster"}, {"scene_cache", "miss"}}},
      {"warnings", {"KHR_materials_sheen ignored"}},
      {"request_id", "4f1c2a"},
  };
}

TEST(ResponseSchema, ValidatesASampleResponse) {
  valijson::Schema schema;
  compileSchema(bundleSchema("render-response.schema.json"), schema);
  EXPECT_EQ(validationErrors(schema, sampleResponse()), std::vector<std::string>{});

  json withExtra = sampleResponse();
  withExtra["device"]["gpu_temperature"] = 70;
  EXPECT_FALSE(validationErrors(schema, withExtra).empty());

  json badClock = sampleResponse();
  badClock["timings"][0]["clock"] = "wall";
  EXPECT_FALSE(validationErrors(schema, badClock).empty());

  json missingId = sampleResponse();
  missingId.erase("request_id");
  EXPECT_FALSE(validationErrors(schema, missingId).empty());
}

}  // namespace
}  // namespace lgh

// --- Enum names ---------------------------------------------------------------------------------

namespace lgh {
namespace {

// The "enum" list of the first property called `property` anywhere in a proto document.
std::vector<std::string> schemaEnum(const std::string& file, const std::string& property) {
  const json document = json::parse(protoDocument(file));
  std::vector<const json*> pending{&document};
  while (!pending.empty()) {
    const json* node = pending.back();
    pending.pop_back();
    if (node->is_object()) {
      const auto properties = node->find("properties");
      if (properties != node->end() && properties->contains(property) &&
          (*properties)[property].contains("enum")) {
        return (*properties)[property]["enum"].get<std::vector<std::string>>();
      }
    }
    if (node->is_structured()) {
      for (const auto& child : *node) pending.push_back(&child);
    }
  }
  return {};
}

template <typename Enum>
std::vector<std::string> tableNames(std::initializer_list<std::string_view> skip = {}) {
  std::vector<std::string> names;
  for (const auto& entry : EnumNames<Enum>::names) {
    if (std::find(skip.begin(), skip.end(), entry.name) == skip.end()) {
      names.emplace_back(entry.name);
    }
  }
  return names;
}

// The parser reads enums through the EnumNames tables: each must list what the schema allows.
TEST(EnumNames, AgreeWithTheSchemas) {
  EXPECT_EQ(schemaEnum("light.schema.json", "type"), tableNames<LightType>());
  EXPECT_EQ(schemaEnum("camera.schema.json", "type"), tableNames<CameraDesc::Kind>({"default"}));
  EXPECT_EQ(schemaEnum("render-request.schema.json", "format"), tableNames<ImageFormat>());
  EXPECT_EQ(schemaEnum("render-request.schema.json", "tone_map"), tableNames<ToneMap>());
  EXPECT_EQ(schemaEnum("render-settings.schema.json", "method"), tableNames<LghBuildMethod>());
  EXPECT_EQ(schemaEnum("render-settings.schema.json", "interleave"), tableNames<InterleaveMode>());
  EXPECT_EQ(schemaEnum("render-settings.schema.json", "path"), tableNames<LightingPath>());
  EXPECT_EQ(schemaEnum("render-settings.schema.json", "texture_compression"),
            tableNames<TextureCompression>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "model"), tableNames<MaterialModel>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "shading"), tableNames<ShadingMode>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "surface"), tableNames<SurfaceDetail>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "alpha_mode"), tableNames<AlphaMode>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "wrap_s"), tableNames<WrapMode>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "wrap_t"), tableNames<WrapMode>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "filter"), tableNames<TextureFilter>());
  EXPECT_EQ(schemaEnum("material-parameters.schema.json", "mipmaps"), tableNames<MipmapMode>());
  EXPECT_EQ(schemaEnum("scene.schema.json", "builtin"), tableNames<BuiltinScene>());
}

// --- Global illumination and built-in scenes (docs/GI.md) ---------------------------------------

TEST(RequestParse, GiSettingsAndBuiltinScenes) {
  const RenderRequest request = parseRenderRequest(
      R"({"scene": {"builtin": "atrium"},
          "settings": {"gi": {"enabled": true, "bounces": 2, "vpl_count": 5000, "seed": 9},
                       "lgh": {"alpha": 2, "frame": 3, "shadow_jitter": 0.5}}})");
  EXPECT_EQ(request.scene.kind, SceneSource::Kind::Builtin);
  EXPECT_EQ(request.scene.builtin, BuiltinScene::Atrium);
  EXPECT_TRUE(request.settings.gi.enabled);
  EXPECT_TRUE(request.settings.lgh.enabled) << "GI lights the frame through the LGH";
  EXPECT_EQ(request.settings.gi.bounces, 2);
  EXPECT_EQ(request.settings.gi.vplCount, 5000);
  EXPECT_EQ(request.settings.gi.seed, 9U);
  EXPECT_EQ(request.settings.lgh.frame, 3U);
  EXPECT_FLOAT_EQ(request.settings.lgh.shadowJitter, 0.5F);
  EXPECT_EQ(parseRenderRequest(R"({"scene": {"builtin": "demo"}})").scene.builtin,
            BuiltinScene::Demo);
}

TEST(RequestErrors, GiFieldsAreChecked) {
  const auto code = [](const std::string& text) { return parseError(text); };
  EXPECT_EQ(code(R"({"settings": {"gi": {"bounces": 4}}})").field(), "/settings/gi/bounces");
  EXPECT_EQ(code(R"({"settings": {"gi": {"bounces": 4}}})").code(), kInvalid);
  EXPECT_EQ(code(R"({"settings": {"gi": {"vpl_count": 0}}})").field(), "/settings/gi/vpl_count");
  EXPECT_EQ(code(R"({"settings": {"gi": {"sun": 1}}})").field(), "/settings/gi/sun");
  EXPECT_EQ(code(R"({"scene": {"builtin": "nave"}})").field(), "/scene/builtin");
  EXPECT_EQ(code(R"({"settings": {"lgh": {"shadow_jitter": 2}}})").field(),
            "/settings/lgh/shadow_jitter");
  RequestLimits limits;
  limits.maxVpls = 1000;
  const Error tooMany = parseError(
      std::string(R"({"settings": {"gi": {"enabled": true, "vpl_count": 1001}}})"), limits);
  EXPECT_EQ(tooMany.code(), ErrorCode::TooLarge);
  EXPECT_EQ(tooMany.field(), "/settings/gi/vpl_count");
}

TEST(EnumNames, RoundTripAndAliases) {
  EXPECT_EQ(enumName(InterleaveMode::Tiles4x4), "4x4");
  EXPECT_EQ(enumFromName<InterleaveMode>("2x2"), InterleaveMode::Tiles2x2);
  EXPECT_EQ(enumFromName<ImageFormat>("exr"), ImageFormat::ExrHalf);
  EXPECT_EQ(enumName(ImageFormat::ExrHalf), "exr");  // the first name is the canonical one
  EXPECT_FALSE(enumFromName<ToneMap>("filmic").has_value());
  EXPECT_EQ(enumNameList<ToneMap>(), "none, reinhard, aces");
}

}  // namespace
}  // namespace lgh

// --- Discriminated oneOf, and the other request schemas
// -------------------------------------------

namespace lgh {
namespace {

// valijson knows no discriminator: the bundle lowers the camera's oneOf to one if/then per type,
// so that an error is the selected camera's (see schema_bundle.hpp). The file keeps the oneOf.
TEST(SchemaBundle, LowersADiscriminatedOneOfToIfThen) {
  const json document = json::parse(protoDocument("camera.schema.json"));
  EXPECT_EQ(document.at("discriminator").at("propertyName"), "type");
  EXPECT_EQ(document.at("oneOf").size(), 3U);

  const json bundle = bundleSchema("camera.schema.json");
  EXPECT_FALSE(bundle.contains("oneOf"));
  EXPECT_FALSE(bundle.contains("discriminator"));
  ASSERT_EQ(bundle.at("allOf").size(), 3U);
  for (const json& branch : bundle.at("allOf")) {
    const std::string type = branch.at("if").at("properties").at("type").at("const");
    EXPECT_EQ(branch.at("then").at("$ref"), "#/$defs/" + type);
    EXPECT_EQ(document.at("discriminator").at("mapping").at(type), "#/$defs/" + type);
  }
}

Error schemaError(const json& value, const std::string& file) {
  try {
    validateAgainstProtoSchema(value, file);
  } catch (const Error& error) {
    return error;
  }
  ADD_FAILURE() << file << " accepted " << value.dump();
  return Error(ErrorCode::Internal, "no error");
}

TEST(ProtoSchemas, ThumbnailsRequestNamesTheField) {
  const std::string file = "thumbnails-request.schema.json";
  EXPECT_NO_THROW(validateAgainstProtoSchema(json::object(), file));
  EXPECT_NO_THROW(validateAgainstProtoSchema(
      {{"assets", {"a.glb"}}, {"views", {{{"name", "front"}, {"direction", {0, 0, 1}}}}}}, file));

  Error unknown = schemaError({{"colour", "red"}}, file);
  EXPECT_EQ(unknown.field(), "/colour");
  EXPECT_NE(std::string(unknown.message()).find("allowed here: assets"), std::string::npos)
      << unknown.message();
  EXPECT_EQ(schemaError({{"width", 0}}, file).code(), ErrorCode::Invalid);
  EXPECT_EQ(schemaError({{"format", "tar"}}, file).field(), "/format");
  const Error badName =
      schemaError({{"views", {{{"name", "a b"}, {"direction", {0, 0, 1}}}}}}, file);
  EXPECT_EQ(badName.field(), "/views/0/name");
  EXPECT_NE(std::string(badName.message()).find("must match"), std::string::npos)
      << badName.message();
  EXPECT_EQ(schemaError({{"views", {{{"name", "a"}}}}}, file).field(), "/views/0/direction");
}

TEST(ProtoSchemas, JobRequestSelectsTheKindsSchema) {
  const std::string file = "job-request.schema.json";
  EXPECT_NO_THROW(validateAgainstProtoSchema({{"kind", "render"}}, file));
  EXPECT_NO_THROW(validateAgainstProtoSchema(
      {{"kind", "thumbnails"}, {"request", {{"assets", {"a.glb"}}}}}, file));
  EXPECT_NO_THROW(validateAgainstProtoSchema({{"kind", "benchmark"}, {"iterations", 3}}, file));

  EXPECT_EQ(schemaError({{"kind", "bake"}}, file).field(), "/kind");
  EXPECT_EQ(schemaError(json::object(), file).field(), "/kind");
  EXPECT_EQ(schemaError({{"kind", "thumbnails"}}, file).field(), "/request");
  // Only the selected kind's members are allowed, and errors reach into its request.
  EXPECT_EQ(schemaError({{"kind", "render"}, {"iterations", 3}}, file).field(), "/iterations");
  const Error width =
      schemaError({{"kind", "render"}, {"request", {{"output", {{"width", 0}}}}}}, file);
  EXPECT_EQ(width.field(), "/request/output/width");
  EXPECT_EQ(width.code(), ErrorCode::Invalid);
  EXPECT_EQ(schemaError({{"kind", "thumbnails"}, {"request", {{"width", "big"}}}}, file).field(),
            "/request/width");
}

}  // namespace
}  // namespace lgh
