// Analytic checks of the lecture's illumination models and glTF's GGX, run on the shader's own
// BRDF (glsl/include/brdf.glsl through the test kernel glsl/brdf_probe.comp, on llvmpipe):
//  - Oren-Nayar at sigma 0 is Lambert: rho / pi cos(theta_i), to float rounding;
//  - Phong peaks where R.V = 1 and Blinn-Phong where N.H = 1 (both: V the mirror direction of L),
//    with the lecture's peak of 1 (times 1/pi, docs/MATERIALS.md);
//  - Cook-Torrance and GGX are reciprocal: f(l, v) = f(v, l);
//  - white furnace: the directional albedo (the integral of BRDF x cos over the hemisphere of
//    lights) of the microfacet lobes (Cook-Torrance with F0 = 1, GGX metal) stays at most 1, and
//    near 1 where a smooth metal reflects nearly all light; Cook-Torrance with a white diffuse
//    base too, at every angle. glTF's GGX dielectric weights its diffuse base by 1 - F(H.V) (the
//    specification's fresnel_mix), which gains energy at grazing views: bounded at 0 and 30
//    degrees here, the grazing figures printed (docs/MATERIALS.md).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "context/gl_context.hpp"
#include "gl/shader_library.hpp"
#include "lgh/material_settings.hpp"
#include "test_support.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

struct ProbeInput {
  glm::vec4 baseColorModel;
  glm::vec4 specularExponent;
  glm::vec4 metallicRoughness;
  glm::vec4 toViewer;
  glm::vec4 toLight;
};

struct Material {
  lgh::MaterialModel model = lgh::MaterialModel::MetallicRoughness;
  glm::vec3 baseColor{1.0F};
  glm::vec3 specular{0.0F};
  float exponent = 1.0F;
  float metallic = 0.0F;
  float roughness = 0.5F;
};

struct Lobes {
  glm::vec3 diffuse;
  glm::vec3 specular;
  glm::vec3 sum() const { return diffuse + specular; }
};

glm::vec3 direction(double theta, double phi) {
  return {static_cast<float>(std::sin(theta) * std::cos(phi)),
          static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))};
}

class BrdfModels : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    program = std::make_unique<lgh::gl::Program>(lgh::gl::buildComputeProgram("brdf_probe.comp"));
  }
  static void TearDownTestSuite() {
    program.reset();
    context.reset();
  }

  // The shader's lobes for each (viewer, light) pair.
  static std::vector<Lobes> evaluate(const Material& m,
                                     const std::vector<std::pair<glm::vec3, glm::vec3>>& pairs) {
    std::vector<ProbeInput> inputs;
    inputs.reserve(pairs.size());
    for (const auto& [viewer, light] : pairs) {
      inputs.push_back({glm::vec4(m.baseColor, static_cast<float>(m.model)),
                        glm::vec4(m.specular, m.exponent),
                        glm::vec4(m.metallic, m.roughness, 0.0F, 0.0F), glm::vec4(viewer, 0.0F),
                        glm::vec4(light, 0.0F)});
    }
    lgh::gl::Buffer inputBuffer;
    glNamedBufferStorage(inputBuffer.id(),
                         static_cast<GLsizeiptr>(inputs.size() * sizeof(ProbeInput)), inputs.data(),
                         0);
    lgh::gl::Buffer outputBuffer;
    std::vector<glm::vec4> outputs(inputs.size() * 2);
    glNamedBufferStorage(outputBuffer.id(),
                         static_cast<GLsizeiptr>(outputs.size() * sizeof(glm::vec4)), nullptr, 0);
    glUseProgram(program->id());
    glUniform1ui(glGetUniformLocation(program->id(), "uCount"), static_cast<GLuint>(inputs.size()));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, inputBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, outputBuffer.id());
    glDispatchCompute(static_cast<GLuint>((inputs.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(outputBuffer.id(), 0,
                            static_cast<GLsizeiptr>(outputs.size() * sizeof(glm::vec4)),
                            outputs.data());
    glUseProgram(0);
    std::vector<Lobes> lobes;
    lobes.reserve(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      lobes.push_back({glm::vec3(outputs[2 * i]), glm::vec3(outputs[2 * i + 1])});
    }
    return lobes;
  }

  // Directional albedo for a viewer at theta_v: the midpoint rule over the hemisphere of light
  // directions, of the lobes (which carry the cosine): luminance-free, the red channel.
  static double albedo(const Material& m, double thetaV, int steps = 384) {
    const glm::vec3 viewer = direction(thetaV, 0.0);
    std::vector<std::pair<glm::vec3, glm::vec3>> pairs;
    std::vector<double> solidAngles;
    const double dTheta = kPi / 2.0 / steps;
    const double dPhi = 2.0 * kPi / (2 * steps);
    for (int i = 0; i < steps; ++i) {
      const double theta = (i + 0.5) * dTheta;
      for (int j = 0; j < 2 * steps; ++j) {
        const double phi = (j + 0.5) * dPhi;
        pairs.emplace_back(viewer, direction(theta, phi));
        solidAngles.push_back(std::sin(theta) * dTheta * dPhi);
      }
    }
    const std::vector<Lobes> lobes = evaluate(m, pairs);
    double sum = 0.0;
    for (std::size_t k = 0; k < lobes.size(); ++k) sum += lobes[k].sum().r * solidAngles[k];
    return sum;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::gl::Program> program;
};

std::vector<std::pair<glm::vec3, glm::vec3>> randomPairs(int count, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<glm::vec3, glm::vec3>> pairs;
  for (int i = 0; i < count; ++i) {
    // Uniform over the hemisphere (cos theta uniform), away from exactly grazing.
    auto sample = [&] {
      return direction(std::acos(0.02 + 0.98 * unit(random)), 2.0 * kPi * unit(random));
    };
    pairs.emplace_back(sample(), sample());
  }
  return pairs;
}

TEST_F(BrdfModels, OrenNayarAtSigmaZeroIsLambert) {
  Material lambert;
  lambert.model = lgh::MaterialModel::OrenNayar;
  lambert.baseColor = glm::vec3(0.8F, 0.5F, 0.2F);
  lambert.exponent = 0.0F;  // sigma
  const auto pairs = randomPairs(4000, 7);
  const auto lobes = evaluate(lambert, pairs);
  double worst = 0.0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const glm::vec3 expected =
        lambert.baseColor * static_cast<float>(1.0 / kPi) * pairs[i].second.z;
    for (int c = 0; c < 3; ++c) {
      worst = std::max(
          worst, static_cast<double>(std::abs(lobes[i].diffuse[c] - expected[c]) / expected[c]));
    }
    EXPECT_EQ(lobes[i].specular, glm::vec3(0.0F));
  }
  std::cout << fmt::format("Oren-Nayar sigma 0 vs Lambert: largest relative difference {:.2e}\n",
                           worst);
  EXPECT_LT(worst, 1e-5);

  // Rough surfaces are "not so dimmed" (the lecture): seen and lit from the same grazing side,
  // sigma 0.5 returns more light than Lambert.
  Material rough = lambert;
  rough.exponent = 0.5F;
  const glm::vec3 grazing = direction(70.0 * kPi / 180.0, 0.3);
  const auto retro = evaluate(rough, {{grazing, grazing}});
  const auto flat = evaluate(lambert, {{grazing, grazing}});
  EXPECT_GT(retro[0].diffuse.r, 1.2F * flat[0].diffuse.r);
}

// L at 40 degrees; V swept over the hemisphere: both lobes peak at the mirror direction, where
// R.V = 1 and N.H = 1, with the lecture's peak of 1 (x specular / pi).
TEST_F(BrdfModels, PhongAndBlinnPhongPeakAtTheMirrorDirection) {
  const double thetaL = 40.0 * kPi / 180.0;
  const glm::vec3 light = direction(thetaL, 0.0);
  const glm::vec3 mirror = direction(thetaL, kPi);
  constexpr int kSteps = 180;
  std::vector<std::pair<glm::vec3, glm::vec3>> pairs;
  for (int i = 0; i < kSteps; ++i) {
    for (int j = 0; j < 2 * kSteps; ++j) {
      const double theta = (i + 0.5) * (kPi / 2.0) / kSteps;
      const double phi = j * 2.0 * kPi / (2 * kSteps);
      pairs.emplace_back(direction(theta, phi), light);
    }
  }
  pairs.emplace_back(mirror, light);  // the exact peak
  for (const auto model : {lgh::MaterialModel::Phong, lgh::MaterialModel::BlinnPhong}) {
    SCOPED_TRACE(std::string(lgh::enumName(model)));
    Material m;
    m.model = model;
    m.baseColor = glm::vec3(0.5F);
    m.specular = glm::vec3(1.0F);
    m.exponent = 60.0F;
    const auto lobes = evaluate(m, pairs);
    std::size_t best = 0;
    for (std::size_t k = 0; k < lobes.size(); ++k) {
      if (lobes[k].specular.r > lobes[best].specular.r) best = k;
    }
    const glm::vec3 viewer = pairs[best].first;
    EXPECT_NEAR(glm::dot(viewer, mirror), 1.0F, 1e-5F);
    const glm::vec3 reflected = -light + 2.0F * light.z * glm::vec3(0, 0, 1);
    const glm::vec3 half = glm::normalize(light + viewer);
    EXPECT_NEAR(glm::dot(reflected, viewer), 1.0F, 1e-5F) << "R.V at the peak";
    EXPECT_NEAR(half.z, 1.0F, 1e-5F) << "N.H at the peak";
    EXPECT_NEAR(lobes[best].specular.r, 1.0 / kPi, 1e-5) << "the lecture's peak of 1, / pi";
    // And it falls off away from it: 10 degrees off the mirror direction in the plane of
    // incidence, Phong's (cos 10)^60 = 0.40, Blinn-Phong's (cos 5)^60 = 0.80.
    const glm::vec3 off = direction(thetaL + 10.0 * kPi / 180.0, kPi);
    const auto offLobes = evaluate(m, {{off, light}});
    const double expected =
        std::pow(std::cos((model == lgh::MaterialModel::Phong ? 10.0 : 5.0) * kPi / 180.0), 60.0) /
        kPi;
    EXPECT_NEAR(offLobes[0].specular.r, expected, 1e-4);
  }
}

TEST_F(BrdfModels, CookTorranceAndGgxAreReciprocal) {
  const auto pairs = randomPairs(4000, 11);
  std::vector<std::pair<glm::vec3, glm::vec3>> swapped;
  swapped.reserve(pairs.size());
  for (const auto& [v, l] : pairs) swapped.emplace_back(l, v);
  Material cookTorrance;
  cookTorrance.model = lgh::MaterialModel::CookTorrance;
  cookTorrance.baseColor = glm::vec3(0.6F, 0.3F, 0.1F);
  cookTorrance.specular = glm::vec3(0.9F, 0.6F, 0.3F);  // F0
  cookTorrance.exponent = 0.35F;                        // m
  Material ggx;
  ggx.baseColor = glm::vec3(0.6F, 0.3F, 0.1F);
  ggx.metallic = 0.3F;
  ggx.roughness = 0.5F;
  for (const Material& m : {cookTorrance, ggx}) {
    SCOPED_TRACE(std::string(lgh::enumName(m.model)));
    const auto forward = evaluate(m, pairs);
    const auto backward = evaluate(m, swapped);
    double worst = 0.0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      // The lobes carry N.L: the BRDF is lobes / N.L.
      const glm::vec3 f = forward[i].sum() / pairs[i].second.z;
      const glm::vec3 g = backward[i].sum() / swapped[i].second.z;
      for (int c = 0; c < 3; ++c) {
        const double scale = std::max({std::abs(f[c]), std::abs(g[c]), 1e-6F});
        worst = std::max(worst, static_cast<double>(std::abs(f[c] - g[c]) / scale));
      }
    }
    std::cout << fmt::format("{}: reciprocity, largest relative difference {:.2e}\n",
                             lgh::enumName(m.model), worst);
    EXPECT_LT(worst, 1e-4);
  }
}

TEST_F(BrdfModels, WhiteFurnaceBounds) {
  struct Case {
    std::string name;
    Material material;
    double lowerAtNormal;     // the albedo at normal incidence is at least this
    double boundedUpTo = 90;  // view angles (degrees) up to which the albedo is at most 1
  };
  std::vector<Case> cases;
  for (const float m : {0.15F, 0.3F, 0.6F, 1.0F}) {
    Material metal;
    metal.model = lgh::MaterialModel::CookTorrance;
    metal.baseColor = glm::vec3(0.0F);
    metal.specular = glm::vec3(1.0F);
    metal.exponent = m;
    cases.push_back({fmt::format("cook-torrance F0 1, m {}", m), metal, m <= 0.3F ? 0.95 : 0.4});
    Material plastic = metal;
    plastic.baseColor = glm::vec3(1.0F);
    plastic.specular = glm::vec3(0.04F);
    cases.push_back({fmt::format("cook-torrance white plastic, m {}", m), plastic, 0.88});
  }
  for (const float roughness : {0.4F, 0.6F, 0.8F, 1.0F}) {
    Material metal;
    metal.baseColor = glm::vec3(1.0F);
    metal.metallic = 1.0F;
    metal.roughness = roughness;
    cases.push_back(
        {fmt::format("ggx metal, roughness {}", roughness), metal, roughness <= 0.4F ? 0.95 : 0.3});
    Material dielectric = metal;
    dielectric.metallic = 0.0F;
    cases.push_back(
        {fmt::format("ggx white dielectric, roughness {}", roughness), dielectric, 0.95, 30.0});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::string line = fmt::format("white furnace, {:<34}", c.name);
    for (const double degrees : {0.0, 30.0, 60.0, 80.0}) {
      const double a = albedo(c.material, degrees * kPi / 180.0);
      line += fmt::format(" {:>4.0f}deg {:.3f}", degrees, a);
      // 0.5% for the quadrature of the peaked lobes.
      if (degrees <= c.boundedUpTo) EXPECT_LE(a, 1.005) << degrees << " degrees";
      if (degrees == 0.0) EXPECT_GE(a, c.lowerAtNormal);
    }
    std::cout << line << "\n";
  }
}

}  // namespace
