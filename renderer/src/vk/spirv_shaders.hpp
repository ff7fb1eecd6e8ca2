// The tracer's shaders (glsl/vk/) as SPIR-V, compiled by glslc at build time and embedded
// (cmake/Spirv.cmake generates the definitions, named after the files).
#pragma once

#include <cstdint>
#include <span>

namespace lgh::vk::spirv {

std::span<const std::uint32_t> shadow_ray_query_comp();
std::span<const std::uint32_t> shadow_ray_rgen();
std::span<const std::uint32_t> shadow_ray_rmiss();
std::span<const std::uint32_t> closest_hit_query_comp();
std::span<const std::uint32_t> closest_hit_rgen();
std::span<const std::uint32_t> closest_hit_rmiss();
std::span<const std::uint32_t> closest_hit_rchit();
std::span<const std::uint32_t> gi_emit_comp();
std::span<const std::uint32_t> gi_bounce_comp();

}  // namespace lgh::vk::spirv
