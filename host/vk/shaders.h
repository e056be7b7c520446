// The SPIR-V of kernels/vk/*, compiled by glslc at build time and embedded in the binary
// (no shader files to find at run time).
#pragma once

#include <cstdint>
#include <span>

namespace gc::vk::shaders {

std::span<const std::uint32_t> raster_vert();
std::span<const std::uint32_t> raster_frag();
std::span<const std::uint32_t> aov_comp();
std::span<const std::uint32_t> path_comp();
std::span<const std::uint32_t> whitted_comp();
std::span<const std::uint32_t> aov_instances_comp();      // aov.comp, GC_SCENE_INSTANCED
std::span<const std::uint32_t> path_instances_comp();     // path.comp, GC_SCENE_INSTANCED
std::span<const std::uint32_t> whitted_instances_comp();  // whitted.comp, GC_SCENE_INSTANCED

}  // namespace gc::vk::shaders
