#include "host/render/denoise_guides.h"

#include <algorithm>

namespace gc {
namespace {

Film render_aov(const Renderer& beauty, AovKind kind, std::uint32_t spp)
{
    RenderSettings settings = beauty.settings();
    settings.integrator = IntegratorKind::Aov;
    settings.aov = kind;
    settings.spp = spp;
    settings.time_limit_seconds = 0;
    Renderer renderer(beauty.context(), beauty.shared_scene(), beauty.camera(), settings, beauty.setup());
    renderer.render(0, spp);
    return renderer.film();
}

}  // namespace

DenoiseGuides render_denoise_guides(const Renderer& beauty, std::uint32_t beauty_spp)
{
    const std::uint32_t spp = std::max(k_guide_spp, beauty_spp);
    DenoiseGuides guides;
    guides.albedo = render_aov(beauty, AovKind::GuideAlbedo, spp);
    guides.normal = render_aov(beauty, AovKind::GuideNormal, spp);
    return guides;
}

}  // namespace gc
