#include "scene_compare.hpp"

#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace lgh::test {
namespace {

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameTexture(const TextureRef& a, const TextureRef& b, std::size_t slot) {
  SCOPED_TRACE("texture slot " + std::to_string(slot));
  EXPECT_EQ(a.image, b.image);
  EXPECT_EQ(a.texCoord, b.texCoord);
  EXPECT_EQ(a.sampler.magFilter, b.sampler.magFilter);
  EXPECT_EQ(a.sampler.minFilter, b.sampler.minFilter);
  EXPECT_EQ(a.sampler.wrapS, b.sampler.wrapS);
  EXPECT_EQ(a.sampler.wrapT, b.sampler.wrapT);
  EXPECT_EQ(a.sampler.borderColor, b.sampler.borderColor);
  EXPECT_EQ(a.sampler.anisotropy, b.sampler.anisotropy);
  EXPECT_EQ(a.transform.offset, b.transform.offset);
  EXPECT_EQ(a.transform.rotation, b.transform.rotation);
  EXPECT_EQ(a.transform.scale, b.transform.scale);
}

void expectSameMaterial(const Material& a, const Material& b) {
  SCOPED_TRACE("material " + a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.baseColorFactor, b.baseColorFactor);
  EXPECT_EQ(a.metallicFactor, b.metallicFactor);
  EXPECT_EQ(a.roughnessFactor, b.roughnessFactor);
  EXPECT_EQ(a.emissiveFactor, b.emissiveFactor);
  EXPECT_EQ(a.normalScale, b.normalScale);
  EXPECT_EQ(a.occlusionStrength, b.occlusionStrength);
  EXPECT_EQ(a.alphaMode, b.alphaMode);
  EXPECT_EQ(a.alphaCutoff, b.alphaCutoff);
  EXPECT_EQ(a.doubleSided, b.doubleSided);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.clearcoat.factor, b.clearcoat.factor);
  EXPECT_EQ(a.clearcoat.roughness, b.clearcoat.roughness);
  EXPECT_EQ(a.clearcoat.normalScale, b.clearcoat.normalScale);
  EXPECT_EQ(a.sheen.colorFactor, b.sheen.colorFactor);
  EXPECT_EQ(a.sheen.roughnessFactor, b.sheen.roughnessFactor);
  EXPECT_EQ(a.specular.factor, b.specular.factor);
  EXPECT_EQ(a.specular.colorFactor, b.specular.colorFactor);
  EXPECT_EQ(a.specular.ior, b.specular.ior);
  EXPECT_EQ(a.transmission.factor, b.transmission.factor);
  EXPECT_EQ(a.transmission.thicknessFactor, b.transmission.thicknessFactor);
  EXPECT_EQ(a.transmission.attenuationColor, b.transmission.attenuationColor);
  EXPECT_EQ(a.transmission.attenuationDistance, b.transmission.attenuationDistance);
  EXPECT_EQ(a.classic.ambient, b.classic.ambient);
  EXPECT_EQ(a.classic.specular, b.classic.specular);
  EXPECT_EQ(a.classic.shininess, b.classic.shininess);
  EXPECT_EQ(a.classic.sigma, b.classic.sigma);
  EXPECT_EQ(a.classic.m, b.classic.m);
  EXPECT_EQ(a.classic.f0, b.classic.f0);
  EXPECT_EQ(a.classic.shading, b.classic.shading);
  expectSameTexture(a.classic.specularTexture, b.classic.specularTexture, 100);
  expectSameTexture(a.classic.shininessTexture, b.classic.shininessTexture, 101);
  EXPECT_EQ(a.surface.technique, b.surface.technique);
  EXPECT_EQ(a.surface.heightScale, b.surface.heightScale);
  EXPECT_EQ(a.surface.parallaxBias, b.surface.parallaxBias);
  EXPECT_EQ(a.surface.reliefLinearSteps, b.surface.reliefLinearSteps);
  EXPECT_EQ(a.surface.reliefBinarySteps, b.surface.reliefBinarySteps);
  EXPECT_EQ(a.surface.reliefSelfShadow, b.surface.reliefSelfShadow);
  EXPECT_EQ(a.surface.reliefSilhouettes, b.surface.reliefSilhouettes);
  EXPECT_EQ(a.surface.tessellationPixels, b.surface.tessellationPixels);
  EXPECT_EQ(a.surface.tessellationMaxLevel, b.surface.tessellationMaxLevel);
  expectSameTexture(a.surface.heightTexture, b.surface.heightTexture, 102);
  expectSameTexture(a.lightMap, b.lightMap, 103);
  EXPECT_EQ(a.lightMapStrength, b.lightMapStrength);
  EXPECT_EQ(a.bicubic, b.bicubic);
  EXPECT_EQ(a.hasLayers(), b.hasLayers());
  const auto slotsA = materialTextureSlots(a);
  const auto slotsB = materialTextureSlots(b);
  for (std::size_t i = 0; i < slotsA.size(); ++i) {
    expectSameTexture(*slotsA[i].texture, *slotsB[i].texture, i);
    EXPECT_EQ(slotsA[i].usage, slotsB[i].usage);
  }
}

void expectSamePrimitives(const std::vector<Primitive>& a, const std::vector<Primitive>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t p = 0; p < a.size(); ++p) {
    SCOPED_TRACE("primitive " + std::to_string(p));
    EXPECT_TRUE(sameBytes(a[p].vertices, b[p].vertices));
    EXPECT_EQ(a[p].indices, b[p].indices);
    EXPECT_EQ(a[p].material, b[p].material);
    EXPECT_EQ(a[p].topology, b[p].topology);
    EXPECT_EQ(a[p].unlit, b[p].unlit);
    EXPECT_EQ(a[p].tangents, b[p].tangents);
  }
}

// Every field of Scene the renderer reads.
}  // namespace

void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t m = 0; m < a.meshes.size(); ++m) {
    SCOPED_TRACE("mesh " + std::to_string(m));
    EXPECT_EQ(a.meshes[m].name, b.meshes[m].name);
    expectSamePrimitives(a.meshes[m].primitives, b.meshes[m].primitives);
    expectSamePrimitives(a.meshes[m].linesAndPoints, b.meshes[m].linesAndPoints);
  }
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (std::size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].mesh, b.instances[i].mesh);
    EXPECT_EQ(a.instances[i].world, b.instances[i].world);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    expectSameMaterial(a.materials[i], b.materials[i]);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].width, b.images[i].width);
    EXPECT_EQ(a.images[i].height, b.images[i].height);
    EXPECT_EQ(a.images[i].channels, b.images[i].channels);
    EXPECT_TRUE(sameBytes(a.images[i].pixels, b.images[i].pixels));
  }
  ASSERT_EQ(a.compressedImages.size(), b.compressedImages.size());
  for (const auto& [index, blocks] : a.compressedImages) {
    SCOPED_TRACE("compressed image " + std::to_string(index));
    ASSERT_EQ(b.compressedImages.count(index), 1U);
    const BlockCompressedImage& other = b.compressedImages.at(index);
    EXPECT_EQ(blocks.format, other.format);
    EXPECT_EQ(blocks.srgb, other.srgb);
    EXPECT_EQ(blocks.width, other.width);
    EXPECT_EQ(blocks.height, other.height);
    EXPECT_EQ(blocks.levels, other.levels);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (std::size_t i = 0; i < a.textures.size(); ++i) {
    expectSameTexture(a.textures[i], b.textures[i], 200 + i);
  }
  EXPECT_TRUE(sameBytes(a.lights, b.lights));
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (std::size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
    EXPECT_EQ(a.cameras[i].world, b.cameras[i].world);
    EXPECT_EQ(a.cameras[i].yfov, b.cameras[i].yfov);
  }
  EXPECT_EQ(a.bounds.min, b.bounds.min);
  EXPECT_EQ(a.bounds.max, b.bounds.max);
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.triangleCount(), b.triangleCount());
  EXPECT_EQ(a.lineAndPointPrimitiveCount(), b.lineAndPointPrimitiveCount());
}

}  // namespace lgh::test
