#include "lgh/testing/lgh_cpu_reference.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {
namespace {

constexpr std::size_t kBlock = 1024;

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

// The 9 accumulated sums of one grid vertex (see glsl/include/lgh_types.glsl).
struct Sums {
  glm::dvec3 rgb{0.0};
  glm::dvec3 m1{0.0};  // sum w I u
  glm::dvec3 m2{0.0};  // sum w I (u^2 + var / h^2)
};

struct LevelGrid {
  int level = 0;
  int e = 0;  // 2^e cells along the longest axis
  glm::uvec3 dims{0U};
  double h = 0.0;
  std::size_t vertices() const { return std::size_t{dims.x} * dims.y * dims.z; }
  std::uint32_t encode(const glm::uvec3& v) const { return v.x + dims.x * (v.y + dims.y * v.z); }
  glm::uvec3 decode(std::uint32_t index) const {
    const std::uint32_t plane = dims.x * dims.y;
    const std::uint32_t z = index / plane;
    const std::uint32_t rest = index - z * plane;
    return {rest % dims.x, rest / dims.x, z};
  }
};

std::vector<const PointLight*> contributingLights(const std::vector<PointLight>& lights) {
  std::size_t invalid = 0;
  std::vector<const PointLight*> contributing;
  for (const PointLight& light : lights) {
    if (!lghValidLight(light)) {
      ++invalid;
    } else if (lghLuminance(glm::vec3(light.intensityPad)) > 0.0F) {
      contributing.push_back(&light);
    }
  }
  if (invalid > 0) {
    throw Error(ErrorCode::Invalid,
                fmt::format("{} of {} point lights have a NaN, infinite or out-of-range position "
                            "or intensity",
                            invalid, lights.size()),
                "lights");
  }
  return contributing;
}

// Calls visit(corner vertex, axis weights (double), u) for the corners with non-zero weight of a
// point at grid coordinate t (float, as the kernels compute it).
template <typename Visit>
void forEachCorner(const glm::vec3& t, Visit&& visit) {
  const glm::vec3 i0 = glm::floor(t);
  const glm::vec3 f = t - i0;  // exact in float
  for (int corner = 0; corner < 8; ++corner) {
    glm::uvec3 vertex(i0);
    glm::dvec3 weight(0.0);
    glm::dvec3 u(0.0);
    bool zero = false;
    for (int a = 0; a < 3; ++a) {
      const bool high = (corner >> a & 1) != 0;
      const double fa = f[a];
      weight[a] = high ? fa : 1.0 - fa;
      u[a] = high ? fa - 1.0 : fa;
      vertex[a] += high ? 1U : 0U;
      zero = zero || weight[a] <= 0.0;
    }
    if (!zero) visit(vertex, weight.x * weight.y * weight.z, u);
  }
}

std::uint32_t countS1(const std::vector<const PointLight*>& lights, const LghGridGeometry& grid,
                      int candidate) {
  const int e = candidate - 1;
  const glm::uvec3 dims = grid.dims(e);
  std::vector<bool> occupied(std::size_t{dims.x} * dims.y * dims.z, false);
  std::uint32_t count = 0;
  for (const PointLight* light : lights) {
    forEachCorner(grid.gridCoordinate(glm::vec3(light->positionPad), e),
                  [&](const glm::uvec3& v, double, const glm::dvec3&) {
                    const std::size_t index = v.x + dims.x * (v.y + std::size_t{dims.y} * v.z);
                    if (!occupied[index]) ++count;
                    occupied[index] = true;
                  });
  }
  return count;
}

std::vector<Sums> scatterLevel(const std::vector<const PointLight*>& lights,
                               const LghGridGeometry& grid, const LevelGrid& level) {
  std::vector<Sums> sums(level.vertices());
  for (const PointLight* light : lights) {
    const glm::dvec3 rgb(glm::vec3(light->intensityPad));
    const double lum = luminance(rgb);
    forEachCorner(grid.gridCoordinate(glm::vec3(light->positionPad), level.e),
                  [&](const glm::uvec3& v, double w, const glm::dvec3& u) {
                    Sums& s = sums[level.encode(v)];
                    s.rgb += w * rgb;
                    s.m1 += w * lum * u;
                    s.m2 += w * lum * u * u;
                  });
  }
  return sums;
}

// Grid lights of the occupied vertices, in vertex order.
std::vector<LghReferenceLight> finalizeLevel(const std::vector<Sums>& sums,
                                             const LghGridGeometry& grid, const LevelGrid& level) {
  std::vector<LghReferenceLight> lights;
  for (std::uint32_t index = 0; index < sums.size(); ++index) {
    const Sums& s = sums[index];
    const double w = luminance(s.rgb);
    if (!(w > 0.0)) continue;
    LghReferenceLight light;
    light.vertex = index;
    light.coords = level.decode(index);
    light.intensity = s.rgb;
    light.luminance = w;
    light.offsetCells = glm::clamp(s.m1 / w, -1.0, 1.0);
    light.varianceCells = glm::max(s.m2 / w - light.offsetCells * light.offsetCells, 0.0);
    light.center =
        glm::dvec3(grid.origin) + (glm::dvec3(light.coords) + light.offsetCells) * level.h;
    light.variance = light.varianceCells * (level.h * level.h);
    lights.push_back(light);
  }
  return lights;
}

// Level l from the S1 grid lights: every vertex visits the S1 vertices within s = 2^(l-1) S1
// cells per axis and weighs each S1 light by the level-l trilinear weight of its centre.
std::vector<Sums> gatherLevel(const LghReferenceLevel& s1, const LevelGrid& level) {
  std::vector<const LghReferenceLight*> dense(std::size_t{s1.dims.x} * s1.dims.y * s1.dims.z);
  for (const LghReferenceLight& light : s1.lights) dense[light.vertex] = &light;
  const int s = 1 << (level.level - 1);
  const glm::ivec3 d1(s1.dims);
  std::vector<Sums> sums(level.vertices());
  for (std::uint32_t index = 0; index < sums.size(); ++index) {
    const glm::ivec3 k = glm::ivec3(level.decode(index)) * s;
    const glm::ivec3 lo = glm::max(k - s, glm::ivec3(0));
    const glm::ivec3 hi = glm::min(k + s, d1 - 1);
    Sums& sum = sums[index];
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
          const LghReferenceLight* light =
              dense[x + d1.x * (y + static_cast<std::size_t>(d1.y) * z)];
          if (light == nullptr) continue;
          const glm::dvec3 u =
              (glm::dvec3(x - k.x, y - k.y, z - k.z) + light->offsetCells) / double(s);
          const glm::dvec3 axis = 1.0 - glm::abs(u);
          if (axis.x <= 0.0 || axis.y <= 0.0 || axis.z <= 0.0) continue;
          const double w = axis.x * axis.y * axis.z;
          sum.rgb += w * light->intensity;
          sum.m1 += w * light->luminance * u;
          sum.m2 += w * light->luminance * (u * u + light->varianceCells / double(s * s));
        }
      }
    }
  }
  return sums;
}

int chooseLevels(const std::vector<const PointLight*>& lights, const LghGridGeometry& grid, int fit,
                 std::vector<std::uint32_t>& candidates) {
  candidates.assign(static_cast<std::size_t>(fit), 0);
  for (int L = 1; L <= fit; ++L) candidates[L - 1] = countS1(lights, grid, L);
  for (int L = fit; L >= 1; --L) {
    if (2 * std::size_t{candidates[L - 1]} < lights.size()) return L;
  }
  return 1;
}

}  // namespace

LghGridGeometry LghGridGeometry::fromBounds(const glm::vec3& lo, const glm::vec3& hi) {
  LghGridGeometry grid;
  grid.origin = lo;
  grid.boundsMax = hi;
  grid.extent = hi - lo;
  const glm::vec3 absMax = glm::max(glm::abs(lo), glm::abs(hi));
  const float maxAbs = std::max(absMax.x, std::max(absMax.y, absMax.z));
  const float longest = std::max(grid.extent.x, std::max(grid.extent.y, grid.extent.z));
  grid.top = std::max(longest, std::max(1.0e-6F, 1.0e-4F * maxAbs));
  grid.invTop = 1.0F / grid.top;
  return grid;
}

glm::uvec3 LghGridGeometry::dims(int e) const {
  const float cells = static_cast<float>(1U << e);
  const glm::vec3 t = extent * (invTop * cells);
  return glm::uvec3(glm::ceil(glm::min(t, glm::vec3(cells)))) + 1U;
}

std::size_t LghGridGeometry::denseTotal(int levels) const {
  std::size_t total = 0;
  for (int e = 0; e < levels; ++e) {
    const glm::uvec3 d = dims(e);
    const double product = double(d.x) * d.y * d.z;
    if (product > 2147483648.0) return SIZE_MAX;
    total += (std::size_t{d.x} * d.y * d.z + kBlock - 1) / kBlock * kBlock;
  }
  return total;
}

int LghGridGeometry::fitLevels(std::size_t budget) const {
  for (int levels = kLghMaxLevels; levels > 1; --levels) {
    if (denseTotal(levels) <= budget) return levels;
  }
  return 1;
}

glm::vec3 LghGridGeometry::gridCoordinate(const glm::vec3& p, int e) const {
  const float cells = static_cast<float>(1U << e);
  const glm::vec3 t = (p - origin) * (invTop * cells);
  return glm::min(t, glm::vec3(cells));
}

LghReference buildLghReference(const std::vector<PointLight>& lights,
                               const LghBuildSettings& settings, std::size_t denseBudget) {
  const std::vector<const PointLight*> contributing = contributingLights(lights);
  LghReference reference;
  reference.contributingCount = contributing.size();
  if (contributing.empty()) return reference;
  glm::vec3 lo(3.0e38F);
  glm::vec3 hi(-3.0e38F);
  for (const PointLight* light : contributing) {
    lo = glm::min(lo, glm::vec3(light->positionPad));
    hi = glm::max(hi, glm::vec3(light->positionPad));
    reference.totalIntensity += glm::dvec3(glm::vec3(light->intensityPad));
  }
  reference.grid = LghGridGeometry::fromBounds(lo, hi);
  const LghGridGeometry& grid = reference.grid;
  reference.fitLevels = grid.fitLevels(
      denseBudget > 0 ? denseBudget : lghResolveDenseBudget(lights.size(), settings));
  const int levelCount = settings.levels > 0 ? std::min(settings.levels, reference.fitLevels)
                                             : chooseLevels(contributing, grid, reference.fitLevels,
                                                            reference.candidateS1);
  reference.levelCount = levelCount;
  for (int l = 1; l <= levelCount; ++l) {
    LevelGrid level;
    level.level = l;
    level.e = levelCount - l;
    level.dims = grid.dims(level.e);
    level.h = std::ldexp(grid.top, -level.e);
    const bool gather = settings.method == LghSettings::Method::Gather && l > 1;
    const std::vector<Sums> sums =
        gather ? gatherLevel(reference.levels[0], level) : scatterLevel(contributing, grid, level);
    reference.levels.push_back({l, level.h, level.dims, finalizeLevel(sums, grid, level)});
  }
  return reference;
}

}  // namespace lgh
