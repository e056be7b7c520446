// The scene features an OpenCL program is built for (kernels/shared/gc_features.h): each
// program is compiled without the code for features its scene lacks — textures, normal maps,
// alpha MASK and BLEND, point lights, an environment map, each material type and each glTF
// material layer (clearcoat, specular, sheen) — which
// leaves every image bit unchanged and makes PoCL's cold build and the CPU path loop cheaper.
//
//     const KernelFeatures features = kernel_features(materials, point_lights, has_env_map);
//     cl::Program program(context, "megakernel.cl", program_options(features));
//
// KernelFeatureSet::All builds the full program instead (for A/B comparisons and the tests
// that check the bits agree).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "gc_types.h"
#include "host/render/device_tuning.h"

namespace gc {

struct KernelFeatures {
    bool textures = true;
    bool normal_maps = true;
    bool alpha_mask = true;
    bool alpha_blend = true;
    bool point_lights = true;
    bool env_map = true;
    bool clearcoat = true;  // the KHR_materials_* layers of GC_MAT_PBR (GC_MATF_CLEARCOAT, ...)
    bool specular = true;
    bool sheen = true;
    bool rough_transmission = true;  // GC_MATF_ROUGH_TRANSMISSION
    bool volume = true;              // GC_MATF_VOLUME
    std::uint32_t material_types = 0xffffffffu;  // bit t: some material has type t (GC_MAT_*)

    bool operator==(const KernelFeatures&) const = default;
};

// What the scene with these device materials and lights uses; every feature on for
// KernelFeatureSet::All.
KernelFeatures kernel_features(std::span<const dev::GcMaterial> materials, std::size_t point_lights, bool env_map,
                               KernelFeatureSet set = KernelFeatureSet::Scene);

// "-D GC_USE_TEXTURES=0 ..." for the features that are off (and GC_USE_MATERIALS when not
// every type is present); "" for the full program.
std::string program_options(const KernelFeatures& features);

}  // namespace gc
