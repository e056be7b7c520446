#include "host/vk/shaders.h"

namespace gc::vk::shaders {
namespace {

// glslc -mfmt=c writes each module as a braced list of 32-bit words.
constexpr std::uint32_t kRasterVert[] =
#include "raster.vert.inc"
    ;
constexpr std::uint32_t kRasterFrag[] =
#include "raster.frag.inc"
    ;
constexpr std::uint32_t kAovComp[] =
#include "aov.comp.inc"
    ;
constexpr std::uint32_t kPathComp[] =
#include "path.comp.inc"
    ;
constexpr std::uint32_t kWhittedComp[] =
#include "whitted.comp.inc"
    ;
constexpr std::uint32_t kAovInstancesComp[] =
#include "aov_instances.comp.inc"
    ;
constexpr std::uint32_t kPathInstancesComp[] =
#include "path_instances.comp.inc"
    ;
constexpr std::uint32_t kWhittedInstancesComp[] =
#include "whitted_instances.comp.inc"
    ;

}  // namespace

std::span<const std::uint32_t> raster_vert() { return kRasterVert; }
std::span<const std::uint32_t> raster_frag() { return kRasterFrag; }
std::span<const std::uint32_t> aov_comp() { return kAovComp; }
std::span<const std::uint32_t> path_comp() { return kPathComp; }
std::span<const std::uint32_t> whitted_comp() { return kWhittedComp; }
std::span<const std::uint32_t> aov_instances_comp() { return kAovInstancesComp; }
std::span<const std::uint32_t> path_instances_comp() { return kPathInstancesComp; }
std::span<const std::uint32_t> whitted_instances_comp() { return kWhittedInstancesComp; }

}  // namespace gc::vk::shaders
