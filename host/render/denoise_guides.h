// The guides a denoiser takes beside the beauty: albedo and shading normal, rendered by the
// aov integrator with the beauty's scene, camera, size and seed.
#pragma once

#include <cstdint>

#include "host/image/film.h"
#include "host/render/renderer.h"

namespace gc {

struct DenoiseGuides {
    Film albedo;
    Film normal;
};

// k_guide_spp samples per pixel (more when the beauty has more): enough that the guides are
// noise-free (OIDN's cleanAux) apart from what the albedo's anti-aliasing leaves.
inline constexpr std::uint32_t k_guide_spp = 64;

DenoiseGuides render_denoise_guides(const Renderer& beauty);

}  // namespace gc
