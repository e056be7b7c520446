#include "host/render/session.h"

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <variant>

#include "host/render/environment.h"
#include "host/scene/load.h"
#include "host/util/log.h"

namespace gc {
namespace {

using Clock = std::chrono::steady_clock;

std::string seconds_since(Clock::time_point start)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.3f s", std::chrono::duration<double>(Clock::now() - start).count());
    return text;
}

// The file, instanced where the request keeps instances and the file reuses a mesh; the
// instances' two-level BVH parts too when `with_bvh` (the flat BVH is prepare_scene's).
PreparedScene load_prepared(const SceneRequest& request, bool with_bvh)
{
    const auto start = Clock::now();
    PreparedScene prepared;
    std::optional<Bounds3> world_bounds;
    std::variant<Scene, InstancedScene> loaded = request.keep_instances
                                                     ? load_scene_keeping_instances(request.path, request.load)
                                                     : load_scene(request.path, request.load);
    if (InstancedScene* instanced = std::get_if<InstancedScene>(&loaded)) {
        auto instances = std::make_shared<PreparedInstances>();
        prepared.scene = instanced->meshes;
        instances->scene = std::move(*instanced);
        world_bounds = gc::world_bounds(instances->scene);
        log_verbose("instanced: " + std::to_string(instances->scene.mesh_ranges.size()) + " meshes drawn by " +
                    std::to_string(instances->scene.instances.size()) + " instances (" +
                    std::to_string(instances->scene.instanced_triangle_count()) + " triangles drawn)");
        log_verbose("loaded " + request.path.string() + ": " + std::to_string(prepared.scene.triangle_count()) +
                    " mesh triangles, " + std::to_string(prepared.scene.materials.size()) + " materials in " +
                    seconds_since(start));
        if (with_bvh) {
            const auto bvh_start = Clock::now();
            instances->bvh = build_instance_bvh(instances->scene);
            log_verbose("two-level BVH: " + std::to_string(instances->bvh.meshes.size()) + " mesh trees, " +
                        std::to_string(instances->bvh.tlas.size()) + " top-level nodes, built in " +
                        seconds_since(bvh_start));
        }
        prepared.instances = std::move(instances);
    } else {
        prepared.scene = std::move(std::get<Scene>(loaded));
        log_verbose("loaded " + request.path.string() + ": " + std::to_string(prepared.scene.triangle_count()) +
                    " triangles, " + std::to_string(prepared.scene.materials.size()) + " materials in " +
                    seconds_since(start));
    }
    prepared.camera = resolve_camera(prepared.scene, request.camera, world_bounds);
    return prepared;
}

DeviceScene upload_prepared(const cl::Context& context, const PreparedScene& prepared, const RenderSettings& settings,
                            const RenderSetup& setup)
{
    const EnvironmentMap environment = load_environment_map(settings);
    if (!prepared.instances) return DeviceScene::upload(context, prepared.scene, prepared.bvh, environment, setup.tuning);
    return DeviceScene::upload_instanced(context, prepared.instances->scene, prepared.instances->bvh, environment,
                                         setup.tuning);
}

}  // namespace

PreparedScene load_with_camera(const SceneRequest& request) { return load_prepared(request, false); }

PreparedScene prepare_scene(const SceneRequest& request)
{
    PreparedScene prepared = load_prepared(request, true);
    if (prepared.instances) return prepared;
    const auto start = Clock::now();
    prepared.bvh = build_bvh(prepared.scene);
    const BvhStats stats = bvh_stats(prepared.bvh);
    char cost[32];
    std::snprintf(cost, sizeof cost, "%.2f", stats.sah_cost);
    log_verbose("BVH: " + std::to_string(stats.nodes) + " nodes, SAH cost " + cost + ", built in " +
                seconds_since(start));
    return prepared;
}

Session::Session(const cl::DeviceInfo& device, const PreparedScene& prepared, const RenderSettings& settings,
                 const RenderSetup& setup)
    : m_context(device),
      m_scene(std::make_shared<DeviceScene>(upload_prepared(m_context, prepared, settings, setup))),
      m_renderer(m_context, m_scene, prepared.camera, settings, setup)
{
}

RenderOutcome Session::render(const RenderControl& control)
{
    return render_to(m_renderer, m_renderer.settings().spp, control);
}

}  // namespace gc
