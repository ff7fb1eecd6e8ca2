#include "thumbnails.hpp"

#include <cctype>
#include <set>

#include <fmt/format.h>

namespace lghd {
namespace {

using json = nlohmann::json;

struct View {
  std::string name;
  json direction;
};

struct Options {
  ThumbnailBatch::Format format = ThumbnailBatch::Format::Zip;
  std::string nameTemplate = "{name}_{view}.png";
  std::vector<std::string> assets;
  std::vector<View> views;
};

// proto/thumbnails-request.schema.json is the contract: members, types, ranges and defaults. The
// checks below it are what a schema cannot say (unique view names, placeholders, views or
// view_direction), and the render request each view becomes is validated as POST /v1/render's.
void checkSchema(const json& body) {
  if (!body.is_object()) throw badRequest("the thumbnail request must be a JSON object", "/");
  try {
    lgh::validateAgainstProtoSchema(body, "thumbnails-request.schema.json");
  } catch (const lgh::Error& error) {
    throw fromLghError(error);
  }
}

std::vector<std::string> readAssets(const json& body) {
  std::vector<std::string> assets;
  const auto it = body.find("assets");
  if (it == body.end()) return assets;
  if (!it->is_array()) throw badRequest("must be an array of asset paths", "/assets");
  for (std::size_t i = 0; i < it->size(); ++i) {
    if (!(*it)[i].is_string()) {
      throw badRequest("must be a string (a path in the asset root)", fmt::format("/assets/{}", i));
    }
    assets.push_back((*it)[i].get<std::string>());
  }
  return assets;
}

bool isViewName(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  }
  return true;
}

std::vector<View> readViews(const json& body) {
  const auto it = body.find("views");
  if (it == body.end()) return {{"default", body.value("view_direction", json{1, 0.6, 1.4})}};
  if (body.contains("view_direction")) {
    throw badRequest("give views or view_direction, not both", "/views");
  }
  if (!it->is_array() || it->empty()) {
    throw badRequest("must be a non-empty array of {name, direction}", "/views");
  }
  std::vector<View> views;
  std::set<std::string> names;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const json& view = (*it)[i];
    const std::string field = fmt::format("/views/{}", i);
    if (!view.is_object() || !view.contains("direction") || view.size() > 2) {
      throw badRequest("must be an object {\"name\", \"direction\"}", field);
    }
    const std::string name = view.value("name", fmt::format("view{}", i));
    if (!isViewName(name) || !names.insert(name).second) {
      throw badRequest("must be a unique name of 1..64 letters, digits, _ or -", field + "/name");
    }
    views.push_back({name, view["direction"]});
  }
  return views;
}

Options readOptions(const json& body) {
  checkSchema(body);
  Options options;
  const json format = body.value("format", json("zip"));
  if (format == "ndjson") {
    options.format = ThumbnailBatch::Format::Ndjson;
  } else if (format != "zip") {
    throw badRequest("must be \"zip\" or \"ndjson\"", "/format");
  }
  if (body.contains("name_template")) {
    if (!body["name_template"].is_string() || body["name_template"].get<std::string>().empty()) {
      throw badRequest("must be a non-empty string", "/name_template");
    }
    options.nameTemplate = body["name_template"].get<std::string>();
  }
  expandNameTemplate(options.nameTemplate, "x", "x", 0);  // checks the placeholders
  options.assets = readAssets(body);
  options.views = readViews(body);
  return options;
}

// The render request every item of one view shares, in the render API's own format, so that it
// gets the same validation and limits as POST /v1/render.
json requestJson(const json& body, const View& view) {
  json camera = {{"type", "auto"}, {"view_direction", view.direction}};
  if (body.contains("margin")) camera["margin"] = body["margin"];
  json output = {{"width", body.value("width", json(256))},
                 {"height", body.value("height", json(256))},
                 {"format", "png"},
                 {"transparent_background", body.value("transparent_background", json(false))}};
  if (body.contains("png_compression")) output["png_compression"] = body["png_compression"];
  json request = {{"camera", std::move(camera)}, {"output", std::move(output)}};
  if (body.contains("settings")) request["settings"] = body["settings"];
  return request;
}

// A field of the generated request, named as the client wrote it in the batch.
std::string batchField(const std::string& field, const std::string& viewField) {
  static const std::vector<std::pair<std::string, std::string>> kRenames = {
      {"/output/width", "/width"},
      {"/output/height", "/height"},
      {"/output/transparent_background", "/transparent_background"},
      {"/output/png_compression", "/png_compression"},
      {"/output", "/width"},
      {"/camera/view_direction", ""},
      {"/camera/margin", "/margin"},
      {"/camera", ""}};
  for (const auto& [from, to] : kRenames) {
    if (field.starts_with(from)) {
      return (to.empty() ? viewField : to) + field.substr(from.size());
    }
  }
  return field;
}

lgh::RenderRequest viewRequest(const json& body, const View& view, std::size_t viewIndex,
                               const lgh::RequestLimits& limits) {
  const std::string viewField =
      body.contains("views") ? fmt::format("/views/{}/direction", viewIndex) : "/view_direction";
  try {
    return lgh::parseRenderRequest(requestJson(body, view), limits);
  } catch (const lgh::Error& error) {
    ApiError apiError = fromLghError(error);
    throw ApiError(apiError.status(), apiError.code(), apiError.message(),
                   batchField(error.field(), viewField));
  }
}

std::string stemOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

// A ZIP member name that cannot leave the archive's folder when unpacked.
std::string safeFileName(std::string name, std::size_t index) {
  for (char& c : name) {
    if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20) c = '_';
  }
  if (name.empty() || name == "." || name == "..") return fmt::format("thumbnail_{}.png", index);
  return name;
}

std::string uniqueFileName(const std::string& name, std::size_t index,
                           std::set<std::string>& taken) {
  if (taken.insert(name).second) return name;
  const std::size_t dot = name.find_last_of('.');
  std::string unique = dot == std::string::npos || dot == 0
                           ? fmt::format("{}_{}", name, index)
                           : fmt::format("{}_{}{}", name.substr(0, dot), index, name.substr(dot));
  taken.insert(unique);
  return unique;
}

struct AssetSource {
  std::string label;
  std::string field;
  std::optional<lgh::SceneSource> scene;
  std::optional<ApiError> error;
};

AssetSource pathAsset(const std::string& path, std::size_t i) {
  const std::string field = fmt::format("/assets/{}", i);
  if (path.empty()) return {path, field, std::nullopt, badRequest("must not be empty", field)};
  if (path.find('\0') != std::string::npos) {
    return {path, field, std::nullopt, badRequest("must not contain NUL characters", field)};
  }
  lgh::SceneSource scene;
  scene.kind = lgh::SceneSource::Kind::AssetPath;
  scene.assetPath = path;
  scene.displayName = path;
  return {path, field, std::move(scene), std::nullopt};
}

std::vector<AssetSource> assetSources(const Options& options,
                                      const std::vector<UploadedFile>& uploads) {
  std::vector<AssetSource> sources;
  for (std::size_t i = 0; i < options.assets.size(); ++i) {
    sources.push_back(pathAsset(options.assets[i], i));
  }
  for (lgh::SceneSource& scene : uploadedScenes(uploads)) {
    sources.push_back({scene.displayName, "file", std::move(scene), std::nullopt});
  }
  return sources;
}

}  // namespace

std::string expandNameTemplate(const std::string& nameTemplate, const std::string& name,
                               const std::string& view, std::size_t index) {
  std::string out;
  for (std::size_t i = 0; i < nameTemplate.size(); ++i) {
    const char c = nameTemplate[i];
    if (c == '}') throw badRequest("unbalanced '}'", "/name_template");
    if (c != '{') {
      out += c;
      continue;
    }
    const std::size_t close = nameTemplate.find('}', i);
    if (close == std::string::npos) throw badRequest("unbalanced '{'", "/name_template");
    const std::string key = nameTemplate.substr(i + 1, close - i - 1);
    if (key == "name") {
      out += name;
    } else if (key == "view") {
      out += view;
    } else if (key == "index") {
      out += std::to_string(index);
    } else {
      throw badRequest(
          fmt::format("unknown placeholder {{{}}}: use {{name}}, {{view}} or {{index}}", key),
          "/name_template");
    }
    i = close;
  }
  return out;
}

ThumbnailBatch parseThumbnailBatch(const json& body, const std::vector<UploadedFile>& uploads,
                                   const lgh::RequestLimits& limits, int maxBatch) {
  const Options options = readOptions(body);
  const std::vector<AssetSource> sources = assetSources(options, uploads);
  if (sources.empty()) {
    throw badRequest("give at least one asset (assets, or uploaded .glb/.gltf files)", "/assets");
  }
  const std::size_t count = sources.size() * options.views.size();
  if (count > static_cast<std::size_t>(maxBatch)) {
    throw fromLghError(lgh::Error(
        lgh::ErrorCode::TooLarge,
        fmt::format("{} thumbnails (assets x views) is over this server's batch limit of {}", count,
                    maxBatch),
        "/assets"));
  }
  std::vector<lgh::RenderRequest> perView;
  for (std::size_t v = 0; v < options.views.size(); ++v) {
    perView.push_back(viewRequest(body, options.views[v], v, limits));
  }

  ThumbnailBatch batch;
  batch.format = options.format;
  std::set<std::string> taken;
  for (const AssetSource& source : sources) {
    for (std::size_t v = 0; v < options.views.size(); ++v) {
      ThumbnailItem item;
      item.index = batch.items.size();
      item.asset = source.label;
      item.assetField = source.field;
      item.view = options.views[v].name;
      const std::string name =
          expandNameTemplate(options.nameTemplate, stemOf(source.label), item.view, item.index);
      item.fileName = uniqueFileName(safeFileName(name, item.index), item.index, taken);
      item.error = source.error;
      if (source.scene) {
        item.request = perView[v];
        item.request->scene = *source.scene;
      }
      batch.items.push_back(std::move(item));
    }
  }
  return batch;
}

std::string zipCommentNamingGpu(int gpu) {
  return gpu < 0 ? std::string() : nlohmann::json{{"gpu", gpu}}.dump();
}

}  // namespace lghd
