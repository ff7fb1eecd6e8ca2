// GL storage kept across scenes (gl/recycled_objects.hpp): on whichever context path the suite
// runs,
//  - a texture or buffer given back is handed out again for the same shape, and only for it;
//  - beyond the kept bytes the objects kept longest are deleted, and an object that outlives its
//    recycler is deleted when it goes;
//  - buffers are kept by power-of-two size class;
//  - frames of real assets drawn with storage taken over from earlier scenes have the pixels of
//    the same frames drawn by a renderer of their own, and the scene cache counts what it reused.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_helpers.hpp"
#include "gl/recycled_objects.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

using lgh::gl::BufferShape;
using lgh::gl::RecycledBuffers;
using lgh::gl::RecycledTexture;
using lgh::gl::RecycledTextures;
using lgh::gl::TextureShape;
using lgh::test::pixelBytes;
using lgh::test::renderHintedFirst;
using lgh::test::thumbnailRequest;

const TextureShape kSmall{GL_RGBA8, 16, 16, 5};
const TextureShape kSmallSrgb{GL_SRGB8_ALPHA8, 16, 16, 5};
constexpr std::size_t kSmallBytes = 1364;

TEST(RecycledTextures, AGivenBackTextureServesTheSameShapeOnly) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  auto recycler = RecycledTextures::create(1 << 20);
  GLuint first = 0;
  {
    RecycledTexture texture = recycler->take(kSmall, kSmallBytes);
    first = texture.id();
    GLint width = 0;
    glGetTextureLevelParameteriv(first, 0, GL_TEXTURE_WIDTH, &width);
    EXPECT_EQ(width, 16);
    EXPECT_EQ(recycler->stats().kept, 0U);
  }
  EXPECT_EQ(recycler->stats().kept, 1U);
  EXPECT_EQ(recycler->stats().keptBytes, kSmallBytes);
  const RecycledTexture srgb = recycler->take(kSmallSrgb, kSmallBytes);
  EXPECT_NE(srgb.id(), first) << "another format takes new storage";
  const RecycledTexture again = recycler->take(kSmall, kSmallBytes);
  EXPECT_EQ(again.id(), first);
  const auto stats = recycler->stats();
  EXPECT_EQ(stats.taken, 3U);
  EXPECT_EQ(stats.recycled, 1U);
  EXPECT_EQ(stats.kept, 0U);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(RecycledTextures, BeyondTheKeptBytesTheOldestAreDeleted) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  auto recycler = RecycledTextures::create(2 * kSmallBytes);
  std::vector<GLuint> ids;
  {
    std::vector<RecycledTexture> textures;
    for (int i = 0; i < 3; ++i) {
      textures.push_back(recycler->take(kSmall, kSmallBytes));
      ids.push_back(textures.back().id());
    }
  }  // given back first to last
  EXPECT_EQ(recycler->stats().kept, 2U);
  EXPECT_EQ(glIsTexture(ids[0]), GL_FALSE) << "the first given back was deleted";
  EXPECT_EQ(glIsTexture(ids[2]), GL_TRUE);
  // Larger than everything kept may be: deleted at once.
  const TextureShape large{GL_RGBA8, 64, 64, 7};
  GLuint largeId = 0;
  {
    const RecycledTexture texture = recycler->take(large, 4 * kSmallBytes);
    largeId = texture.id();
  }
  EXPECT_EQ(glIsTexture(largeId), GL_FALSE);
  EXPECT_EQ(recycler->stats().kept, 2U);
}

TEST(RecycledTextures, ATextureOutlivingItsRecyclerIsDeletedWhenItGoes) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  auto recycler = RecycledTextures::create(1 << 20);
  auto texture = std::make_unique<RecycledTexture>(recycler->take(kSmall, kSmallBytes));
  const GLuint id = texture->id();
  recycler.reset();
  texture.reset();
  EXPECT_EQ(glIsTexture(id), GL_FALSE);
}

TEST(RecycledBuffers, BuffersAreKeptByPowerOfTwoSizeClass) {
  EXPECT_EQ(BufferShape::holding(1).bytes, BufferShape::kMinBytes);
  EXPECT_EQ(BufferShape::holding(4096).bytes, 4096);
  EXPECT_EQ(BufferShape::holding(4097).bytes, 8192);
  EXPECT_EQ(BufferShape::holding(3 << 20).bytes, 4 << 20);
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  auto recycler = RecycledBuffers::create(1 << 20);
  GLuint first = 0;
  {
    const auto buffer = recycler->take(BufferShape::holding(5000), 8192);
    first = buffer.id();
    GLint64 size = 0;
    glGetNamedBufferParameteri64v(first, GL_BUFFER_SIZE, &size);
    EXPECT_EQ(size, 8192);
  }
  const auto other = recycler->take(BufferShape::holding(100), 4096);
  EXPECT_NE(other.id(), first);
  const auto same = recycler->take(BufferShape::holding(7000), 8192);
  EXPECT_EQ(same.id(), first) << "another size of the same class";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

lgh::RendererOptions cacheOff() {
  lgh::RendererOptions options = lgh::test::rendererOptions();
  options.assetRoot = lgh::test::assimpGltfDir();
  options.sceneCacheBytes = 0;  // every new scene evicts the one before
  return options;
}

TEST(RecycledStorage, FramesOnStorageOfEarlierScenesHaveTheirOwnPixels) {
  // The BoxTextured files share one 256x256 image; ClearCoatTest's textures and the boxes'
  // geometry fall in shared size classes.
  const std::vector<std::string> assets = {
      "BoxTextured-glTF/BoxTextured.gltf",          "ClearCoat-glTF/ClearCoatTest.gltf",
      "BoxTextured-glTF-Embedded/BoxTextured.gltf", "BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
      "BoxTextured-glTF-Binary/BoxTextured.glb",    "ClearCoat-glTF/ClearCoatTest.gltf"};
  std::vector<nlohmann::json> frames;
  frames.reserve(assets.size());
  for (const std::string& asset : assets) frames.push_back(thumbnailRequest(asset, false));
  lgh::Renderer shared(cacheOff());
  const auto recycled = renderHintedFirst(shared, frames);
  ASSERT_EQ(recycled.size(), frames.size());
  const auto stats = shared.sceneCacheStats();
  EXPECT_GE(stats.recycledTextures, 3U) << "the boxes' texture and ClearCoatTest's again";
  EXPECT_GE(stats.recycledBuffers, 6U);
  EXPECT_GT(stats.keptStorageBytes, 0U);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE(assets[i]);
    lgh::Renderer alone(cacheOff());
    const auto own = renderHintedFirst(alone, {frames[i]});
    ASSERT_EQ(own.size(), 1U);
    EXPECT_EQ(pixelBytes(recycled[i]), pixelBytes(own[0]));
  }
}

}  // namespace
