#include "tools/bench/bench_scenes.h"

#include <cstdlib>
#include <filesystem>

#include "host/scene/camera_framing.h"
#include "host/scene/load.h"
#include "host/util/error.h"
#include "tools/bench/large_mesh.h"

namespace gc::bench {
namespace {

namespace fs = std::filesystem;

// The view of ../shared/refs/cornell-original.json (the Mitsuba anchors' camera).
Camera cornell_camera()
{
    Camera c;
    c.look_from = Point3(0.0f, 1.0f, 3.9f);
    c.look_at = Point3(0.0f, 1.0f, 0.0f);
    c.up = Vec3(0.0f, 1.0f, 0.0f);
    c.vfov_degrees = 39.3077f;
    return c;
}

std::optional<BenchScene> from_file(const std::string& name, const fs::path& path, std::string* why)
{
    if (!fs::exists(path)) {
        if (why) *why = path.string() + " not found";
        return std::nullopt;
    }
    LoadOptions options;
    options.phong_as_lambert = true; // as the Mitsuba references treat OBJ illum 2
    BenchScene s;
    s.name = name;
    s.scene = load_scene(path, options);
    s.camera = s.scene.camera ? *s.scene.camera : frame_camera(s.scene);
    return s;
}

}  // namespace

std::vector<std::string> default_scene_names()
{
    return {"cornell", "bunny", "dragon", "large"};
}

std::string default_shared_dir()
{
    if (const char* env = std::getenv("GEOCOLD_SHARED_DIR"); env && *env) return env;
    const fs::path source(GEOCOLD_SOURCE_DIR);
    for (const fs::path& candidate : {source / "shared", source / ".." / "shared"})
        if (fs::exists(candidate / "scenes")) return candidate.lexically_normal().string();
    return (source / ".." / "shared").lexically_normal().string();
}

std::optional<BenchScene> load_bench_scene(const std::string& name, const std::string& shared_dir, std::string* why)
{
    const fs::path source(GEOCOLD_SOURCE_DIR);
    const fs::path shared(shared_dir);
    if (name == "cornell" || name == "tiny") {
        auto s = from_file(name, source / "scenes" / "cornell-box" / "CornellBox-Original.obj", why);
        if (s) {
            s->camera = cornell_camera();
            if (name == "tiny") s->pt_width = s->pt_height = 64;
        }
        return s;
    }
    if (name == "bunny") {
        auto s = from_file(name, shared / "scenes" / "stanford-bunny" / "stanford-bunny.obj", why);
        if (s) s->env = glm::vec3(1.0f);
        return s;
    }
    if (name == "dragon") {
        // The Mitsuba cuda_ad_rgb anchor: the dragon under a constant environment, 320x240.
        auto s = from_file(name, shared / "scenes" / "stanford-dragon-100k" / "dragon.obj", why);
        if (s) {
            s->env = glm::vec3(1.0f);
            s->pt_width = 320;
            s->pt_height = 240;
        }
        return s;
    }
    if (name == "large") {
        BenchScene s;
        s.name = name;
        s.scene = make_large_mesh();
        s.camera.look_from = Point3(3.5f, 4.5f, 12.0f);
        s.camera.look_at = Point3(3.5f, 0.3f, 3.5f);
        s.camera.up = Vec3(0.0f, 1.0f, 0.0f);
        s.camera.vfov_degrees = 45.0f;
        s.env = glm::vec3(0.2f);
        return s;
    }
    throw UsageError("unknown scene '" + name + "' (known: cornell, bunny, dragon, large, tiny)");
}

}  // namespace gc::bench
