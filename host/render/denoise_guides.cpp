#include "host/render/denoise_guides.h"

#include <algorithm>

#include "host/render/aov_layers.h"

namespace gc {

DenoiseGuides render_denoise_guides(const Renderer& beauty, std::uint32_t beauty_spp)
{
    const std::uint32_t spp = std::max(k_guide_spp, beauty_spp);
    DenoiseGuides guides;
    guides.albedo = render_aov_like(beauty, AovKind::GuideAlbedo, spp);
    guides.normal = render_aov_like(beauty, AovKind::GuideNormal, spp);
    return guides;
}

}  // namespace gc
