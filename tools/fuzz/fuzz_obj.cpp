// libFuzzer target for the .obj path of load_scene: the text pre-scan (obj_validate),
// tinyobjloader and the conversion. A gc::Error is the expected answer to a bad file; any
// other exception (std::terminate -> abort) or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>

#include "host/scene/load.h"
#include "host/util/error.h"
#include "tools/fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // The .mtl files an input names are looked up beside it: the same folder, so a fuzzed
    // "mtllib in.obj" re-reads the input as a material library, which is fine.
    static const gc::fuzz::InputFile file("in.obj");
    const auto& path = file.write(data, size);
    try {
        const gc::Scene scene = gc::load_scene(path);
        // Invariants every consumer relies on.
        if (scene.positions.size() != 3 * scene.triangle_count() || scene.materials.empty()) __builtin_trap();
        for (std::uint32_t id : scene.material_ids)
            if (id >= scene.materials.size()) __builtin_trap();
    } catch (const gc::Error&) {
    }
    return 0;
}
