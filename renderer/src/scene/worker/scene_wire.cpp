#include "scene/worker/scene_wire.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <tuple>
#include <type_traits>
#include <utility>

#include <fmt/format.h>

namespace lgh::worker {
namespace {

// Writes values to a Sink: SizeSink counts the bytes, MemorySink copies them.
struct SizeSink {
  std::size_t size = 0;
  void put(const void* /*data*/, std::size_t length) { size += length; }
  void zeros(std::size_t length) { size += length; }
  std::size_t offset() const { return size; }
};

struct MemorySink {
  std::uint8_t* start;
  std::uint8_t* next;
  void put(const void* data, std::size_t length) {
    if (length == 0) return;
    std::memcpy(next, data, length);
    next += length;
  }
  void zeros(std::size_t length) {
    std::memset(next, 0, length);
    next += length;
  }
  std::size_t offset() const { return static_cast<std::size_t>(next - start); }
};

// Arrays start at this alignment from the start of the message (which is page-aligned in the
// shared memory it travels in), so that the reader can copy them as arrays of their type.
constexpr std::size_t kArrayAlignment = 16;

std::size_t paddingAt(std::size_t offset) {
  return (kArrayAlignment - offset % kArrayAlignment) % kArrayAlignment;
}

template <typename Sink>
class Writer {
 public:
  explicit Writer(Sink& sink) : sink_(sink) {}

  template <typename T>
  void pod(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    sink_.put(&value, sizeof(T));
  }
  void size(std::size_t value) { pod(static_cast<std::uint64_t>(value)); }
  void text(const std::string& value) {
    size(value.size());
    sink_.put(value.data(), value.size());
  }
  template <typename T>
  void pods(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T> && alignof(T) <= kArrayAlignment);
    size(values.size());
    sink_.zeros(paddingAt(sink_.offset()));
    sink_.put(values.data(), values.size() * sizeof(T));
  }

 private:
  Sink& sink_;
};

// Encoded of `encode(writer)`, run once to count and once to write.
template <typename Encode>
Encoded encoded(Encode encode) {
  SizeSink counter;
  Writer<SizeSink> counting(counter);
  encode(counting);
  return {counter.size, [encode](std::uint8_t* destination) {
            MemorySink sink{destination, destination};
            Writer<MemorySink> writer(sink);
            encode(writer);
          }};
}

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  // The bytes may be shared with the worker while they are read (its answer arena): each value
  // is copied out once, and the empty asm keeps the compiler from reading it from there again
  // after it was checked.
  template <typename T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    asm volatile("" : "+m"(value));
    return value;
  }
  std::size_t size() {
    const auto value = pod<std::uint64_t>();
    if (value > bytes_.size()) broken("a length past the end");
    return static_cast<std::size_t>(value);
  }
  // A count of items of `itemBytes` each, checked against what is left.
  std::size_t count(std::size_t itemBytes) {
    const std::size_t value = size();
    if (itemBytes > 0 && value > (bytes_.size() - position_) / itemBytes) {
      broken("a count past the end");
    }
    return value;
  }
  // A bool as written by Writer::pod (one byte); any other byte value is refused rather than
  // loaded into a bool.
  bool flag() {
    static_assert(sizeof(bool) == 1);
    const auto value = pod<std::uint8_t>();
    if (value > 1) broken("a flag that is neither 0 nor 1");
    return value == 1;
  }
  std::string text() {
    const std::size_t length = count(1);
    const auto* start = reinterpret_cast<const char*>(take(length));
    return {start, length};
  }
  // One copy, no zero-filling first: the array is aligned for T (Writer::pods) and T is
  // trivially copyable, so its bytes are copied as Ts.
  template <typename T>
  std::vector<T> pods() {
    static_assert(std::is_trivially_copyable_v<T> && alignof(T) <= kArrayAlignment);
    const std::size_t length = size();
    take(paddingAt(position_));
    if (length > (bytes_.size() - position_) / std::max<std::size_t>(sizeof(T), 1)) {
      broken("a count past the end");
    }
    const auto* first = reinterpret_cast<const T*>(take(length * sizeof(T)));
    return std::vector<T>(first, first + length);
  }
  void finish() const {
    if (position_ != bytes_.size()) broken("bytes after the end");
  }

 private:
  const std::uint8_t* take(std::size_t length) {
    if (length > bytes_.size() - position_) broken("a message cut short");
    const std::uint8_t* start = bytes_.data() + position_;
    position_ += length;
    return start;
  }
  [[noreturn]] static void broken(const char* what) {
    throw Error(ErrorCode::Internal,
                fmt::format("the scene parser worker sent a malformed message: {}", what));
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
};

// --- Scene -----------------------------------------------------------------------------------

// The shader's slots 10 and 11 hold either KHR_materials_specular's two textures or the classic
// models' two (scene.hpp, materialTextureSlots): the messages carry all four.
static_assert(std::tuple_size_v<decltype(allMaterialTextures(std::declval<Material&>()))> ==
                  kMaterialTextureSlots + 2,
              "a Material texture the worker's messages do not carry");

template <typename Out>
void writeTexture(Out& out, const TextureRef& texture) {
  out.pod(texture.image);
  out.pod(texture.texCoord);
  out.pod(texture.sampler);
  out.pod(texture.transform);
}

TextureRef readTexture(Reader& in) {
  TextureRef texture;
  texture.image = in.pod<int>();
  texture.texCoord = in.pod<int>();
  texture.sampler = in.pod<Sampler>();
  texture.transform = in.pod<UvTransform>();
  return texture;
}

// The material layers' numbers (their textures travel with the material's other textures).
template <typename Out>
void writeLayers(Out& out, const Material& m) {
  out.pod(m.model);
  out.pod(m.clearcoat.factor);
  out.pod(m.clearcoat.roughness);
  out.pod(m.clearcoat.normalScale);
  out.pod(m.sheen.colorFactor);
  out.pod(m.sheen.roughnessFactor);
  out.pod(m.specular.factor);
  out.pod(m.specular.colorFactor);
  out.pod(m.specular.ior);
  out.pod(m.transmission.factor);
  out.pod(m.transmission.thicknessFactor);
  out.pod(m.transmission.attenuationColor);
  out.pod(m.transmission.attenuationDistance);
}

// The classic models' and the surface detail's numbers, the light map's strength, bicubic.
template <typename Out>
void writeLectureParameters(Out& out, const Material& m) {
  const ClassicMaterial& c = m.classic;
  out.pod(c.ambient.has_value());
  out.pod(c.ambient.value_or(glm::vec3(0.0F)));
  out.pod(c.specular);
  out.pod(c.shininess);
  out.pod(c.sigma);
  out.pod(c.m);
  out.pod(c.f0);
  out.pod(c.shading);
  const SurfaceDetailMaterial& d = m.surface;
  out.pod(d.technique);
  out.pod(d.heightScale);
  out.pod(d.parallaxBias.has_value());
  out.pod(d.parallaxBias.value_or(0.0F));
  out.pod(d.reliefLinearSteps);
  out.pod(d.reliefBinarySteps);
  out.pod(d.reliefSelfShadow);
  out.pod(d.reliefSilhouettes);
  out.pod(d.tessellationPixels);
  out.pod(d.tessellationMaxLevel);
  out.pod(m.lightMapStrength);
  out.pod(m.bicubic);
}

void readLectureParameters(Reader& in, Material& m) {
  ClassicMaterial& c = m.classic;
  const bool hasAmbient = in.flag();
  const auto ambient = in.pod<glm::vec3>();
  if (hasAmbient) c.ambient = ambient;
  c.specular = in.pod<glm::vec3>();
  c.shininess = in.pod<float>();
  c.sigma = in.pod<float>();
  c.m = in.pod<float>();
  c.f0 = in.pod<glm::vec3>();
  c.shading = in.pod<ShadingMode>();
  SurfaceDetailMaterial& d = m.surface;
  d.technique = in.pod<SurfaceDetail>();
  d.heightScale = in.pod<float>();
  const bool hasBias = in.flag();
  const auto bias = in.pod<float>();
  if (hasBias) d.parallaxBias = bias;
  d.reliefLinearSteps = in.pod<int>();
  d.reliefBinarySteps = in.pod<int>();
  d.reliefSelfShadow = in.flag();
  d.reliefSilhouettes = in.flag();
  d.tessellationPixels = in.pod<float>();
  d.tessellationMaxLevel = in.pod<int>();
  m.lightMapStrength = in.pod<float>();
  m.bicubic = in.flag();
}

void readLayers(Reader& in, Material& m) {
  m.model = in.pod<MaterialModel>();
  m.clearcoat.factor = in.pod<float>();
  m.clearcoat.roughness = in.pod<float>();
  m.clearcoat.normalScale = in.pod<float>();
  m.sheen.colorFactor = in.pod<glm::vec3>();
  m.sheen.roughnessFactor = in.pod<float>();
  m.specular.factor = in.pod<float>();
  m.specular.colorFactor = in.pod<glm::vec3>();
  m.specular.ior = in.pod<float>();
  m.transmission.factor = in.pod<float>();
  m.transmission.thicknessFactor = in.pod<float>();
  m.transmission.attenuationColor = in.pod<glm::vec3>();
  m.transmission.attenuationDistance = in.pod<float>();
}

template <typename Out>
void writeMaterial(Out& out, const Material& m) {
  out.text(m.name);
  out.pod(m.baseColorFactor);
  out.pod(m.metallicFactor);
  out.pod(m.roughnessFactor);
  out.pod(m.emissiveFactor);
  out.pod(m.normalScale);
  out.pod(m.occlusionStrength);
  out.pod(m.alphaMode);
  out.pod(m.alphaCutoff);
  out.pod(m.doubleSided);
  writeLayers(out, m);
  writeLectureParameters(out, m);
  for (const TextureRef* texture : allMaterialTextures(m)) writeTexture(out, *texture);
}

Material readMaterial(Reader& in) {
  Material m;
  m.name = in.text();
  m.baseColorFactor = in.pod<glm::vec4>();
  m.metallicFactor = in.pod<float>();
  m.roughnessFactor = in.pod<float>();
  m.emissiveFactor = in.pod<glm::vec3>();
  m.normalScale = in.pod<float>();
  m.occlusionStrength = in.pod<float>();
  m.alphaMode = in.pod<AlphaMode>();
  m.alphaCutoff = in.pod<float>();
  m.doubleSided = in.flag();
  readLayers(in, m);
  readLectureParameters(in, m);
  for (TextureRef* texture : allMaterialTextures(m)) *texture = readTexture(in);
  return m;
}

template <typename Out>
void writeCamera(Out& out, const SceneCamera& c) {
  out.text(c.name);
  out.pod(c.perspective);
  out.pod(c.yfov);
  out.pod(c.aspectRatio);
  out.pod(c.znear);
  out.pod(c.zfar);
  out.pod(c.xmag);
  out.pod(c.ymag);
  out.pod(c.world);
}

SceneCamera readCamera(Reader& in) {
  SceneCamera c;
  c.name = in.text();
  c.perspective = in.flag();
  c.yfov = in.pod<float>();
  c.aspectRatio = in.pod<float>();
  c.znear = in.pod<float>();
  c.zfar = in.pod<float>();
  c.xmag = in.pod<float>();
  c.ymag = in.pod<float>();
  c.world = in.pod<glm::mat4>();
  return c;
}

template <typename Out>
void writePrimitives(Out& out, const std::vector<Primitive>& primitives) {
  out.size(primitives.size());
  for (const Primitive& primitive : primitives) {
    out.pods(primitive.vertices);
    out.pods(primitive.indices);
    out.pod(primitive.material);
    out.pod(primitive.topology);
    out.pod(primitive.unlit);
    out.pod(primitive.tangents);
  }
}

std::vector<Primitive> readPrimitives(Reader& in) {
  std::vector<Primitive> primitives(in.count(8));
  for (Primitive& primitive : primitives) {
    primitive.vertices = in.pods<Vertex>();
    primitive.indices = in.pods<std::uint32_t>();
    primitive.material = in.pod<int>();
    primitive.topology = in.pod<Topology>();
    primitive.unlit = in.flag();
    primitive.tangents = in.flag();
  }
  return primitives;
}

template <typename Out>
void writeScene(Out& out, const Scene& scene) {
  out.text(scene.name);
  out.size(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) {
    out.text(mesh.name);
    writePrimitives(out, mesh.primitives);
    writePrimitives(out, mesh.linesAndPoints);
  }
  out.pods(scene.instances);
  out.size(scene.materials.size());
  for (const Material& material : scene.materials) writeMaterial(out, material);
  out.size(scene.images.size());
  for (const Image8& image : scene.images) {
    out.pod(image.width);
    out.pod(image.height);
    out.pod(image.channels);
    out.pods(image.pixels);
  }
  out.size(scene.compressedImages.size());
  for (const auto& [index, blocks] : scene.compressedImages) {
    out.pod(index);
    out.pod(blocks.format);
    out.pod(blocks.srgb);
    out.pod(blocks.width);
    out.pod(blocks.height);
    out.size(blocks.levels.size());
    for (const std::vector<std::uint8_t>& level : blocks.levels) out.pods(level);
  }
  out.size(scene.textures.size());
  for (const TextureRef& texture : scene.textures) writeTexture(out, texture);
  out.pods(scene.lights);
  out.size(scene.cameras.size());
  for (const SceneCamera& camera : scene.cameras) writeCamera(out, camera);
  out.pod(scene.bounds);
  out.size(scene.warnings.size());
  for (const std::string& warning : scene.warnings) out.text(warning);
}

Scene readScene(Reader& in) {
  Scene scene;
  scene.name = in.text();
  scene.meshes.resize(in.count(8));
  for (Mesh& mesh : scene.meshes) {
    mesh.name = in.text();
    mesh.primitives = readPrimitives(in);
    mesh.linesAndPoints = readPrimitives(in);
  }
  scene.instances = in.pods<MeshInstance>();
  scene.materials.resize(in.count(8));
  for (Material& material : scene.materials) material = readMaterial(in);
  scene.images.resize(in.count(8));
  for (Image8& image : scene.images) {
    image.width = in.pod<int>();
    image.height = in.pod<int>();
    image.channels = in.pod<int>();
    image.pixels = in.pods<std::uint8_t>();
  }
  const std::size_t compressed = in.count(8);
  for (std::size_t i = 0; i < compressed; ++i) {
    const auto index = in.pod<int>();
    BlockCompressedImage blocks;
    blocks.format = in.pod<BlockFormat>();
    blocks.srgb = in.flag();
    blocks.width = in.pod<int>();
    blocks.height = in.pod<int>();
    blocks.levels.resize(in.count(8));
    for (std::vector<std::uint8_t>& level : blocks.levels) level = in.pods<std::uint8_t>();
    if (!scene.compressedImages.emplace(index, std::move(blocks)).second) {
      throw Error(ErrorCode::Internal,
                  "the scene parser worker sent a malformed message: an image compressed twice");
    }
  }
  scene.textures.resize(in.count(8));
  for (TextureRef& texture : scene.textures) texture = readTexture(in);
  scene.lights = in.pods<LightDesc>();
  scene.cameras.resize(in.count(8));
  for (SceneCamera& camera : scene.cameras) camera = readCamera(in);
  scene.bounds = in.pod<Bounds>();
  scene.warnings.resize(in.count(8));
  for (std::string& warning : scene.warnings) warning = in.text();
  return scene;
}

// A DDS payload is uploaded as it is: its format must be one GL knows, its size the decoded
// image's, and every level exactly as long as its blocks (the upload reads that many bytes).
template <typename Bad>
void checkBlocks(const Scene& scene, int index, const BlockCompressedImage& blocks, Bad bad) {
  if (index < 0 || static_cast<std::size_t>(index) >= scene.images.size()) {
    bad("a compressed image's index");
  }
  if (blocks.format > BlockFormat::Bc5) bad("a compressed image's block format");
  const Image8& image = scene.images[static_cast<std::size_t>(index)];
  if (blocks.width != image.width || blocks.height != image.height) {
    bad("a compressed image's size");
  }
  // A full chain down to 1x1 has at most 32 levels of an int's size.
  if (blocks.levels.empty() || blocks.levels.size() > 32) bad("a compressed image's level count");
  int width = blocks.width;
  int height = blocks.height;
  for (const std::vector<std::uint8_t>& level : blocks.levels) {
    if (level.size() != blockLevelBytes(blocks.format, width, height)) {
      bad("a compressed image level's byte count");
    }
    width = std::max(width / 2, 1);
    height = std::max(height / 2, 1);
  }
}

// The daemon's renderer indexes these: a worker must not be able to make it read out of range.
void checkIndices(const Scene& scene) {
  const auto bad = [](const char* what) {
    throw Error(ErrorCode::Internal,
                fmt::format("the scene parser worker sent a scene with {} out of range", what));
  };
  for (const MeshInstance& instance : scene.instances) {
    if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= scene.meshes.size()) {
      bad("an instance's mesh");
    }
  }
  const auto checkPrimitive = [&](const Primitive& primitive) {
    if (primitive.material >= static_cast<int>(scene.materials.size())) bad("a material");
    for (std::uint32_t index : primitive.indices) {
      if (index >= primitive.vertices.size()) bad("a vertex index");
    }
  };
  for (const Mesh& mesh : scene.meshes) {
    // Surface consumers (VPL placement, ray tracing) read triangle lists three indices at a time.
    for (const Primitive& primitive : mesh.primitives) {
      checkPrimitive(primitive);
      if (primitive.topology != Topology::Triangles || primitive.indices.size() % 3 != 0) {
        bad("a triangle list's topology or index count");
      }
    }
    for (const Primitive& primitive : mesh.linesAndPoints) {
      checkPrimitive(primitive);
      const bool lines = primitive.topology == Topology::Lines;
      if ((!lines && primitive.topology != Topology::Points) ||
          (lines && primitive.indices.size() % 2 != 0)) {
        bad("a line or point list's topology or index count");
      }
    }
  }
  const auto known = [](auto value) {
    return std::any_of(EnumNames<decltype(value)>::names.begin(),
                       EnumNames<decltype(value)>::names.end(),
                       [&](const auto& entry) { return entry.value == value; });
  };
  for (const Material& m : scene.materials) {
    if (!known(m.model)) bad("a material model");
    if (!known(m.classic.shading)) bad("a classic material's shading");
    if (!known(m.surface.technique)) bad("a surface detail technique");
    // The shader loops this often per pixel and tessellates this finely (the request schema's
    // ranges, proto/material-parameters.schema.json).
    const SurfaceDetailMaterial& d = m.surface;
    if (d.reliefLinearSteps < 1 || d.reliefLinearSteps > 256 || d.reliefBinarySteps < 0 ||
        d.reliefBinarySteps > 16 || d.tessellationMaxLevel < 1 || d.tessellationMaxLevel > 64 ||
        !(d.tessellationPixels >= 1.0F && d.tessellationPixels <= 1024.0F)) {
      bad("a surface detail's step or tessellation count");
    }
    if (m.alphaMode != AlphaMode::Opaque && m.alphaMode != AlphaMode::Mask &&
        m.alphaMode != AlphaMode::Blend) {
      bad("an alpha mode");
    }
    for (const TextureRef* texture : allMaterialTextures(m)) {
      if (texture->image >= static_cast<int>(scene.images.size())) bad("a texture's image");
    }
  }
  for (const Image8& image : scene.images) {
    const auto expected = static_cast<std::uint64_t>(std::max(image.width, 0)) *
                          static_cast<std::uint64_t>(std::max(image.height, 0)) *
                          static_cast<std::uint64_t>(std::max(image.channels, 0));
    if (image.width <= 0 || image.height <= 0 || expected != image.pixels.size()) bad("an image");
  }
  for (const TextureRef& texture : scene.textures) {
    if (texture.image >= static_cast<int>(scene.images.size())) bad("a texture's image");
  }
  for (const auto& [index, blocks] : scene.compressedImages) {
    checkBlocks(scene, index, blocks, bad);
  }
}

}  // namespace

// --- Jobs --------------------------------------------------------------------------------------

Encoded encodeJob(const LoadJob& job) {
  return encoded([&job](auto& out) {
    const SceneSource& source = job.source;
    out.pod(source.kind);
    out.text(source.assetPath);
    out.pods(source.glbBytes);
    out.text(source.gltfFileName);
    out.size(source.uploadedFiles.size());
    for (const auto& [name, bytes] : source.uploadedFiles) {
      out.text(name);
      out.pods(bytes);
    }
    out.text(source.displayName);
    out.text(job.assetRoot.string());
    out.pod(job.limits);
    const SceneLoadOptions& options = job.options;
    out.pod(options.animation.has_value());
    out.pod(options.animation.value_or(SceneAnimation{}));
    out.text(options.materialVariant);
    out.pod(options.ignoreUnsupportedExtensions);
    out.pod(options.textureCompression);
  });
}

LoadJob decodeJob(std::span<const std::uint8_t> bytes) {
  Reader in(bytes);
  LoadJob job;
  SceneSource& source = job.source;
  source.kind = in.pod<SceneSource::Kind>();
  source.assetPath = in.text();
  source.glbBytes = in.pods<std::uint8_t>();
  source.gltfFileName = in.text();
  const std::size_t files = in.count(16);
  for (std::size_t i = 0; i < files; ++i) {
    std::string name = in.text();
    source.uploadedFiles[name] = in.pods<std::uint8_t>();
  }
  source.displayName = in.text();
  job.assetRoot = in.text();
  job.limits = in.pod<SceneLoadLimits>();
  SceneLoadOptions& options = job.options;
  const bool animated = in.flag();
  const auto animation = in.pod<SceneAnimation>();
  if (animated) options.animation = animation;
  options.materialVariant = in.text();
  options.ignoreUnsupportedExtensions = in.flag();
  options.textureCompression = in.pod<TextureCompression>();
  if (options.textureCompression != TextureCompression::None &&
      options.textureCompression != TextureCompression::Bc) {
    throw Error(ErrorCode::Internal,
                "the scene parser worker got a malformed job: an unknown texture compression");
  }
  in.finish();
  return job;
}

// --- Outcomes ----------------------------------------------------------------------------------

Encoded encodeOutcome(const LoadOutcome& outcome) {
  return encoded([&outcome](auto& out) {
    if (const auto* scene = std::get_if<Scene>(&outcome)) {
      out.pod(std::uint8_t{0});
      writeScene(out, *scene);
      return;
    }
    const Error& error = std::get<Error>(outcome);
    out.pod(std::uint8_t{1});
    out.pod(error.code());
    out.text(error.message());
    out.text(error.field());
  });
}

LoadOutcome decodeOutcome(std::span<const std::uint8_t> bytes) {
  Reader in(bytes);
  const auto tag = in.pod<std::uint8_t>();
  if (tag == 0) {
    Scene scene = readScene(in);
    in.finish();
    checkIndices(scene);
    return scene;
  }
  const auto code = in.pod<ErrorCode>();
  std::string message = in.text();
  std::string field = in.text();
  in.finish();
  const bool known = code >= ErrorCode::BadRequest && code <= ErrorCode::Internal;
  return Error(known ? code : ErrorCode::Internal, std::move(message), std::move(field));
}

}  // namespace lgh::worker
