// The benchmark's scenes: the Cornell box (from the repository), the Stanford bunny and the
// 100k dragon (from the shared scene directory, skipped when absent) and the generated
// 5M-triangle field (tools/bench/large_mesh.h); `tiny` is the --quick smoke-test scene.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host/scene/scene.h"

namespace gc::bench {

struct BenchScene {
    std::string name;
    Scene scene;
    Camera camera;
    int pt_width = 512;      // path-tracing resolution
    int pt_height = 512;
    glm::vec3 env{0.0f};     // constant environment radiance for path tracing
};

std::vector<std::string> default_scene_names();

// nullopt (and *why set) when the scene's file is missing. Throws for an unknown name.
std::optional<BenchScene> load_bench_scene(const std::string& name, const std::string& shared_dir, std::string* why);

// The shared directory: $GEOCOLD_SHARED_DIR, else the first of <source>/shared and
// <source>/../shared that holds scenes/.
std::string default_shared_dir();

}  // namespace gc::bench
