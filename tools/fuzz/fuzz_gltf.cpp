// libFuzzer target for the glTF path of load_scene: .gltf JSON and, when the bytes start with
// the "glTF" magic, the .glb container check and tinygltf's binary reader; then the same
// bytes through load_scene_keeping_instances and the instanced scene's shading data. A gc::Error is the
// expected answer to a bad file; any other exception or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <variant>

#include "host/scene/instances.h"
#include "host/scene/load.h"
#include "host/util/error.h"
#include "tools/fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // One name for both forms: the loader picks the binary reader by the magic bytes.
    static const gc::fuzz::InputFile file("in.gltf");
    const auto& path = file.write(data, size);
    try {
        const gc::Scene scene = gc::load_scene(path);
        if (scene.positions.size() != 3 * scene.triangle_count() || scene.materials.empty()) __builtin_trap();
        for (std::uint32_t id : scene.material_ids)
            if (id >= scene.materials.size()) __builtin_trap();
        for (const gc::Material& m : scene.materials)
            for (int slot : {m.albedo_texture, m.metallic_roughness_texture, m.normal_texture, m.emission_texture})
                if (slot >= static_cast<int>(scene.textures.size())) __builtin_trap();
    } catch (const gc::Error&) {
    }
    // The path integrator's load: a file that reuses a mesh comes back instanced.
    try {
        const auto loaded = gc::load_scene_keeping_instances(path);
        if (const auto* s = std::get_if<gc::InstancedScene>(&loaded)) {
            for (const gc::MeshRange& r : s->mesh_ranges)
                if (r.triangle_count == 0 || std::size_t{r.first_triangle} + r.triangle_count > s->meshes.triangle_count())
                    __builtin_trap();
            for (const gc::Instance& i : s->instances)
                if (i.mesh >= s->mesh_ranges.size()) __builtin_trap();
            const gc::Scene shading = gc::with_world_emitters(*s);
            if (shading.triangle_count() < s->meshes.triangle_count()) __builtin_trap();
            (void)gc::world_bounds(*s);
        }
    } catch (const gc::Error&) {
    }
    return 0;
}
