#include "request/material_parameters.hpp"

#include "lgh/request.hpp"
#include "request/json_read.hpp"

namespace lgh {
namespace {

using json = nlohmann::json;

using json_read::read;
using json_read::readEnum;

void readRgb(const json& object, const char* key, std::optional<Rgb>& out) {
  if (const auto it = object.find(key); it != object.end()) {
    out = Rgb{(*it)[0].get<float>(), (*it)[1].get<float>(), (*it)[2].get<float>()};
  }
}

void readTexture(const json& object, const char* key, int defaultTexCoord,
                 std::optional<TextureChoice>& out) {
  const auto it = object.find(key);
  if (it == object.end()) return;
  TextureChoice choice;
  choice.texture = it->at("texture").get<int>();
  choice.texCoord = it->value("tex_coord", defaultTexCoord);
  out = choice;
}

SamplingParameters readSampling(const json& object) {
  SamplingParameters sampling;
  readEnum(object, "wrap_s", sampling.wrapS);
  readEnum(object, "wrap_t", sampling.wrapT);
  if (const auto it = object.find("border_color"); it != object.end()) {
    sampling.borderColor = std::array<float, 4>{(*it)[0].get<float>(), (*it)[1].get<float>(),
                                                (*it)[2].get<float>(), (*it)[3].get<float>()};
  }
  readEnum(object, "filter", sampling.filter);
  readEnum(object, "mipmaps", sampling.mipmaps);
  read(object, "anisotropy", sampling.anisotropy);
  return sampling;
}

}  // namespace

MaterialParameters readMaterialParameters(const json& object) {
  MaterialParameters p;
  readEnum(object, "model", p.model);
  readEnum(object, "shading", p.shading);
  readRgb(object, "diffuse", p.diffuse);
  read(object, "alpha", p.alpha);
  readRgb(object, "ambient", p.ambient);
  readRgb(object, "specular", p.specular);
  readRgb(object, "emission", p.emission);
  read(object, "shininess", p.shininess);
  read(object, "sigma", p.sigma);
  read(object, "m", p.m);
  readRgb(object, "f0", p.f0);
  read(object, "metallic", p.metallic);
  read(object, "roughness", p.roughness);
  readTexture(object, "diffuse_texture", 0, p.diffuseTexture);
  readTexture(object, "specular_texture", 0, p.specularTexture);
  readTexture(object, "shininess_texture", 0, p.shininessTexture);
  readTexture(object, "light_map", 1, p.lightMap);
  read(object, "light_map_strength", p.lightMapStrength);
  readTexture(object, "normal_texture", 0, p.normalTexture);
  readTexture(object, "height_texture", 0, p.heightTexture);
  readEnum(object, "alpha_mode", p.alphaMode);
  read(object, "alpha_cutoff", p.alphaCutoff);
  read(object, "double_sided", p.doubleSided);
  readEnum(object, "surface", p.surface);
  read(object, "height_scale", p.heightScale);
  read(object, "parallax_bias", p.parallaxBias);
  read(object, "relief_linear_steps", p.reliefLinearSteps);
  read(object, "relief_binary_steps", p.reliefBinarySteps);
  read(object, "relief_self_shadow", p.reliefSelfShadow);
  read(object, "relief_silhouettes", p.reliefSilhouettes);
  read(object, "tessellation_pixels", p.tessellationPixels);
  read(object, "tessellation_max_level", p.tessellationMaxLevel);
  if (const auto it = object.find("sampling"); it != object.end()) p.sampling = readSampling(*it);
  return p;
}

MaterialOverride readMaterialOverride(const json& object) {
  MaterialOverride result;
  const json& match = object.at("match");
  if (const auto name = match.find("name"); name != match.end()) {
    result.match.kind = MaterialMatch::Kind::Name;
    result.match.name = name->get<std::string>();
  } else if (const auto index = match.find("index"); index != match.end()) {
    result.match.kind = MaterialMatch::Kind::Index;
    result.match.index = index->get<int>();
  } else {
    result.match.kind = MaterialMatch::Kind::All;
  }
  result.parameters = readMaterialParameters(object.at("parameters"));
  return result;
}

MaterialParameters parseMaterialParameters(const json& object) {
  validateAgainstProtoSchema(object, "material-parameters.schema.json");
  return readMaterialParameters(object);
}

}  // namespace lgh
