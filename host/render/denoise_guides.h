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

// The guides of a beauty of `beauty_spp` samples, rendered with `like`'s device, scene,
// camera, size and seed (a frame rendered on several devices passes one of its devices' own).
DenoiseGuides render_denoise_guides(const Renderer& like, std::uint32_t beauty_spp);
inline DenoiseGuides render_denoise_guides(const Renderer& beauty)
{
    return render_denoise_guides(beauty, beauty.samples_done());
}

}  // namespace gc
