#include "host/render/aov_layers.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "host/render/chunks.h"
#include "host/util/error.h"

namespace gc {
namespace {

constexpr AovLayer k_all[] = {AovLayer::Albedo,   AovLayer::Normal,   AovLayer::Depth,
                              AovLayer::PrimitiveId, AovLayer::Variance, AovLayer::SampleCount};

// Channels `names` of a film, in RGB order.
std::vector<ExrChannel> film_channels(const Film& film, const std::vector<std::string>& names)
{
    std::vector<ExrChannel> channels;
    for (std::size_t k = 0; k < names.size(); ++k) {
        ExrChannel c{names[k], ExrPixelType::Float, {}};
        c.bits.reserve(film.pixel_count());
        for (std::size_t i = 0; i < film.pixel_count(); ++i) c.bits.push_back(std::bit_cast<std::uint32_t>(film.data()[4 * i + k]));
        channels.push_back(std::move(c));
    }
    return channels;
}

ExrChannel primitive_ids(const Film& film)
{
    ExrChannel c{"id", ExrPixelType::Uint, {}};
    c.bits.reserve(film.pixel_count());
    for (std::size_t i = 0; i < film.pixel_count(); ++i) {
        const float id = film.data()[4 * i];
        c.bits.push_back(id < 0.0f ? 0xffffffffu : static_cast<std::uint32_t>(id));
    }
    return c;
}

}  // namespace

const char* aov_layer_name(AovLayer layer)
{
    switch (layer) {
    case AovLayer::Albedo: return "albedo";
    case AovLayer::Normal: return "normal";
    case AovLayer::Depth: return "depth";
    case AovLayer::PrimitiveId: return "primid";
    case AovLayer::Variance: return "variance";
    case AovLayer::SampleCount: return "sample-count";
    }
    return "?";
}

std::string aov_layer_names()
{
    std::string out;
    for (AovLayer l : k_all) out += (out.empty() ? "" : ", ") + std::string(aov_layer_name(l));
    return out;
}

std::vector<AovLayer> parse_aov_layers(const std::string& list)
{
    std::vector<AovLayer> layers;
    std::size_t p = 0;
    while (p <= list.size()) {
        std::size_t comma = list.find(',', p);
        if (comma == std::string::npos) comma = list.size();
        const std::string name = list.substr(p, comma - p);
        p = comma + 1;
        const AovLayer* found = std::find_if(std::begin(k_all), std::end(k_all),
                                             [&](AovLayer l) { return name == aov_layer_name(l); });
        if (found == std::end(k_all))
            throw UsageError("--aovs: unknown layer '" + name + "' (expected a comma-separated list of " +
                             aov_layer_names() + ")");
        if (std::find(layers.begin(), layers.end(), *found) != layers.end())
            throw UsageError("--aovs: layer '" + name + "' is named twice");
        layers.push_back(*found);
    }
    return layers;
}

Film render_aov_like(const Renderer& like, AovKind kind, std::uint32_t spp)
{
    RenderSettings settings = like.settings();
    settings.integrator = IntegratorKind::Aov;
    settings.aov = kind;
    settings.spp = spp;
    settings.time_limit_seconds = 0;
    Renderer renderer(like.context(), like.shared_scene(), like.camera(), settings, like.setup());
    renderer.render(0, spp);
    return renderer.film();
}

std::vector<ExrPart> render_aov_layers(const Renderer& like, const FilmSums& beauty, const std::vector<AovLayer>& layers)
{
    std::vector<ExrPart> parts;
    for (AovLayer layer : layers) {
        ExrPart part;
        part.name = aov_layer_name(layer);
        switch (layer) {
        case AovLayer::Albedo:
            part.channels = film_channels(render_aov_like(like, AovKind::Albedo, k_aov_layer_spp), {"R", "G", "B"});
            break;
        case AovLayer::Normal:
            part.channels = film_channels(render_aov_like(like, AovKind::Normal, k_aov_layer_spp), {"X", "Y", "Z"});
            break;
        case AovLayer::Depth: part.channels = film_channels(render_aov_like(like, AovKind::Depth, 1), {"Z"}); break;
        case AovLayer::PrimitiveId:
            part.channels = {primitive_ids(render_aov_like(like, AovKind::PrimitiveId, 1))};
            break;
        case AovLayer::Variance: part.channels = film_channels(sample_variance(beauty), {"R", "G", "B"}); break;
        case AovLayer::SampleCount: part.channels = {ExrChannel{"N", ExrPixelType::Uint, beauty.sample_counts}}; break;
        }
        parts.push_back(std::move(part));
    }
    return parts;
}

}  // namespace gc
