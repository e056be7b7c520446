#include "host/app/partial_header.h"

#include "host/render/frame_hash.h"

namespace gc {

PartialImage partial_image_header(const PreparedScene& prepared, const RenderSettings& settings,
                                  const ChunkPlan& plan, const ImageMetadata& meta)
{
    PartialImage part;
    part.width = std::uint32_t(settings.width);
    part.height = std::uint32_t(settings.height);
    part.scene_hash = hash_text(prepared.instances ? scene_content_hash(prepared.instances->scene)
                                                   : scene_content_hash(prepared.scene));
    part.options_hash = hash_text(render_options_hash(settings, prepared.camera, plan.chunk_samples));
    part.seed = settings.seed;
    part.chunk_samples = plan.chunk_samples;
    part.first_sample = plan.first_sample;
    part.end_sample = plan.end_sample;
    part.device = meta.device;
    part.integrator = meta.integrator;
    part.scene = meta.scene;
    return part;
}

}  // namespace gc
