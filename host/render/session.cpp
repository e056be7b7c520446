#include "host/render/session.h"

#include <chrono>
#include <cstdio>
#include <string>

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

}  // namespace

PreparedScene load_with_camera(const SceneRequest& request)
{
    const auto start = Clock::now();
    PreparedScene prepared;
    prepared.scene = load_scene(request.path, request.load);
    log_verbose("loaded " + request.path.string() + ": " + std::to_string(prepared.scene.triangle_count()) +
                " triangles, " + std::to_string(prepared.scene.materials.size()) + " materials in " +
                seconds_since(start));
    prepared.camera = resolve_camera(prepared.scene, request.camera);
    return prepared;
}

PreparedScene prepare_scene(const SceneRequest& request)
{
    PreparedScene prepared = load_with_camera(request);
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
      m_scene(std::make_shared<DeviceScene>(DeviceScene::upload(m_context, prepared.scene, prepared.bvh,
                                                                load_environment_map(settings), setup.tuning))),
      m_renderer(m_context, m_scene, prepared.camera, settings, setup)
{
}

RenderOutcome Session::render(const RenderControl& control)
{
    return render_to(m_renderer, m_renderer.settings().spp, control);
}

}  // namespace gc
