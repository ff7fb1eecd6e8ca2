// Vulkan-Hpp's RAII API as the tracer's files use it. Private to src/vk/: the header is large and
// slow to compile, so nothing outside the tracer's own sources includes it.
//   VK_NO_PROTOTYPES: lghd does not link libvulkan; every entry point comes through the loader
//     that vk::raii::Context opens at run time (machines without Vulkan still run GL).
//   VULKAN_HPP_NO_STRUCT_CONSTRUCTORS: structures are aggregates, filled with designated
//     initializers.
//   VULKAN_HPP_NO_TO_STRING and friends: less to compile; results get their names in
//     vulkan_errors.cpp.
#pragma once

#ifndef VK_NO_PROTOTYPES
#define VK_NO_PROTOTYPES
#endif
#define VULKAN_HPP_NO_STRUCT_CONSTRUCTORS
#define VULKAN_HPP_NO_SMART_HANDLE
#define VULKAN_HPP_NO_TO_STRING
#define VULKAN_HPP_NO_SPACESHIP_OPERATOR
#include <vulkan/vulkan_raii.hpp>
