#include "host/app/aov_output.h"

#include "host/util/log.h"

#ifndef GC_VERSION
#define GC_VERSION "unknown"
#endif

namespace gc {

std::filesystem::path aov_layers_path(const std::filesystem::path& output)
{
    std::filesystem::path path = output;
    path.replace_extension(".aovs.exr");
    return path;
}

void write_aov_layers(const std::vector<AovLayer>& layers, const cl::DeviceInfo& device, const PreparedScene& prepared,
                      const RenderSettings& settings, const RenderSetup& setup, const FilmSums& beauty,
                      const ImageMetadata& meta, const std::filesystem::path& output)
{
    // The layers are AOVs: a session of the AOV integrator (whose program they use), on the
    // frame's camera and size.
    RenderSettings aov_settings = settings;
    aov_settings.integrator = IntegratorKind::Aov;
    const Session session(device, prepared, aov_settings, setup);
    std::vector<ExrPart> parts = render_aov_layers(session.renderer(), beauty, layers);
    for (ExrPart& part : parts)
        part.text = {{"Software", "geocold-cl " GC_VERSION},
                     {"geocold:scene", meta.scene},
                     {"geocold:integrator", meta.integrator},
                     {"geocold:seed", std::to_string(meta.seed)},
                     {"geocold:spp", std::to_string(meta.spp)}};
    const std::filesystem::path path = aov_layers_path(output);
    write_exr(path, std::uint32_t(settings.width), std::uint32_t(settings.height), parts);
    std::string names;
    for (AovLayer l : layers) names += (names.empty() ? "" : ", ") + std::string(aov_layer_name(l));
    log_info("wrote " + path.string() + " (" + names + ")");
}

}  // namespace gc
