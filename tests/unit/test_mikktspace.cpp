// MikkTSpace tangents (scene/mikktspace.hpp) against the reference implementation on a mesh with
// mirrored UVs: three quads of a bent strip whose UVs run forward, mirrored back, and twisted (the
// third quad's two triangles have opposite UV orientation). Shared vertices at the mirror seams
// must get one frame per side.
//
// kReference: the tangents the npm package mikktspace 1.1.1 (a WebAssembly build of the
// reference algorithm) gives for the same corners, unindexed, fed glTF's UVs; w negated, as its
// documentation says glTF's UV convention needs. Rounded to 6 decimals.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mikktspace.hpp"

namespace {

struct ReferenceVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};

const std::vector<ReferenceVertex> kVertices = {
    {{0, 0, 0}, {0, 0, 1}, {0.25F, 0.25F}},
    {{1, 0, 0.05F},
     {-0.0984135662610246F, -0.14762034939153687F, 0.9841356626102459F},
     {0.75F, 0.25F}},
    {{2, 0, 0.2F},
     {-0.18814417367671948F, -0.2822162605150792F, 0.9407208683835974F},
     {0.25F, 0.25F}},
    {{3, 0, 0.45F},
     {-0.26387969828012553F, -0.3958195474201882F, 0.879598994267085F},
     {0.75F, 0.75F}},
    {{0, 1, 0}, {-0.09950371902099893F, 0, 0.9950371902099893F}, {0.25F, 0.75F}},
    {{1, 1, 0.2F},
     {-0.19402850002906638F, -0.14552137502179976F, 0.9701425001453319F},
     {0.75F, 0.75F}},
    {{2, 1, 0.5F},
     {-0.27617238536949706F, -0.276172385369497F, 0.9205746178983235F},
     {0.25F, 0.75F}},
    {{3, 1, 0.9F},
     {-0.3426823495024955F, -0.38551764319030735F, 0.8567058737562386F},
     {0.75F, 0.25F}},
};
const std::vector<std::uint32_t> kIndices = {0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6};

// Per corner of kIndices, in glTF's convention (the package's w negated).
const std::vector<glm::vec4> kReference = {
    {1, 0, 0, -1},
    {0.995118F, -0.007264F, 0.098422F, -1},
    {0.980832F, -0.010698F, 0.194562F, -1},
    {1, 0, 0, -1},
    {0.980832F, -0.010698F, 0.194562F, -1},
    {0.995037F, 0, 0.099504F, -1},
    {-0.994615F, -0.017711F, -0.102118F, 1},
    {-0.981247F, 0.013142F, -0.192307F, 1},
    {-0.95921F, 0.019039F, -0.282051F, 1},
    {-0.994615F, -0.017711F, -0.102118F, 1},
    {-0.95921F, 0.019039F, -0.282051F, 1},
    {-0.980097F, -0.013581F, -0.198056F, 1},
    {0.660871F, 0.672168F, 0.333825F, 1},
    {0.626613F, 0.622934F, 0.468304F, 1},
    {0.607836F, 0.604336F, 0.515086F, 1},
    {0.660871F, 0.672168F, 0.333825F, -1},
    {0.607836F, 0.604336F, 0.515086F, -1},
    {0.650945F, 0.650945F, 0.390567F, -1},
};

lgh::Primitive referenceMesh(bool indexed) {
  lgh::Primitive primitive;
  if (indexed) {
    for (const ReferenceVertex& v : kVertices) {
      lgh::Vertex vertex;
      vertex.position = v.position;
      vertex.normal = v.normal;
      vertex.uv0 = v.uv;
      primitive.vertices.push_back(vertex);
    }
    primitive.indices = kIndices;
    return primitive;
  }
  for (std::uint32_t index : kIndices) {
    lgh::Vertex vertex;
    vertex.position = kVertices[index].position;
    vertex.normal = kVertices[index].normal;
    vertex.uv0 = kVertices[index].uv;
    primitive.indices.push_back(static_cast<std::uint32_t>(primitive.vertices.size()));
    primitive.vertices.push_back(vertex);
  }
  return primitive;
}

void expectReference(const lgh::Primitive& primitive) {
  ASSERT_EQ(primitive.indices.size(), kReference.size());
  for (std::size_t c = 0; c < kReference.size(); ++c) {
    const glm::vec4 t = primitive.vertices.at(primitive.indices[c]).tangent;
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(t[k], kReference[c][k], 2e-5F) << "corner " << c << " component " << k;
    }
  }
}

// Unwelded input (each corner its own vertex): MikkTSpace welds equal vertices itself.
TEST(MikkTSpace, MatchesTheReferenceOnUnweldedCorners) {
  lgh::Primitive primitive = referenceMesh(false);
  lgh::generateMikkTSpaceTangents(primitive);
  expectReference(primitive);
}

// Indexed input: the seam vertices shared by mirrored triangles are split, one per frame.
TEST(MikkTSpace, SplitsSharedVerticesAtMirrorSeams) {
  lgh::Primitive primitive = referenceMesh(true);
  lgh::generateMikkTSpaceTangents(primitive);
  expectReference(primitive);
  EXPECT_GT(primitive.vertices.size(), kVertices.size());
  // The seam vertex 1 (x = 1, y = 0) is on both sides of the first mirror: two frames.
  EXPECT_NE(primitive.indices[1], primitive.indices[6]);
  EXPECT_EQ(primitive.vertices[primitive.indices[1]].position,
            primitive.vertices[primitive.indices[6]].position);
}

// Degenerate UVs and repeated indices give finite, unit frames.
TEST(MikkTSpace, DegenerateInputStaysFinite) {
  lgh::Primitive primitive = referenceMesh(true);
  for (lgh::Vertex& vertex : primitive.vertices) vertex.uv0 = glm::vec2(0.5F);
  primitive.indices.insert(primitive.indices.end(), {0, 0, 1});
  lgh::generateMikkTSpaceTangents(primitive);
  for (const lgh::Vertex& vertex : primitive.vertices) {
    const glm::vec3 t(vertex.tangent);
    EXPECT_NEAR(glm::length(t), 1.0F, 1e-5F);
    EXPECT_EQ(std::abs(vertex.tangent.w), 1.0F);
  }
}

}  // namespace
