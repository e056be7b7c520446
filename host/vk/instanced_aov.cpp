#include "host/vk/instanced_aov.h"

#include "host/vk/compute_reference.h"

namespace gc::vk {

Film render_instanced_aov(const Context& context, const InstancedScene& scene, const InstancedBvh& bvh,
                          const Camera& camera, const RenderSettings& settings)
{
    RenderSettings aov = settings;
    aov.integrator = IntegratorKind::Aov;
    ComputeReference reference(context, scene, bvh, camera, aov);
    reference.render_sample();
    return reference.film();
}

}  // namespace gc::vk
