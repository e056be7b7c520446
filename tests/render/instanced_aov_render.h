// kernels/aov_instances.cl driven directly, for the tests that compare its images.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "host/bvh/instance_bvh.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/program.h"
#include "host/render/device_scene.h"
#include "host/render/integrator.h"

namespace gc::test {

inline cl::Buffer<glm::vec4> zero_film(const cl::Context& context, std::size_t pixels)
{
    auto film = cl::Buffer<glm::vec4>::create(context, pixels, CL_MEM_READ_WRITE, "film");
    film.write(std::vector<glm::vec4>(pixels, glm::vec4(0.0f)));
    return film;
}

inline std::vector<glm::vec4> read_film(const cl::Context& context, const cl::Buffer<glm::vec4>& film, std::size_t pixels)
{
    context.finish();
    std::vector<glm::vec4> out(pixels);
    film.read(out);
    return out;
}

template <class Bvh>
std::vector<glm::vec4> render_instanced_aov_in(const cl::Context& context, const DeviceScene& meshes, const Bvh& bvh,
                                               const dev::GcRenderParams& params)
{
    const cl::Program program(context, "aov_instances.cl", scene_program_options(meshes));
    auto tlas = cl::read_only_buffer(context, bvh.tlas, "tlas");
    auto instances = cl::read_only_buffer(context, bvh.instances, "instances");
    auto nodes = cl::read_only_buffer(context, bvh.nodes, "mesh nodes");
    auto tris = cl::read_only_buffer(context, bvh.tris, "mesh triangles");
    auto film = zero_film(context, params.pixel_count);
    cl::Kernel kernel = program.kernel("aov_instances_render");
    kernel.set_args(params, tlas, instances, nodes, tris, meshes.shade_args(), film);
    kernel.launch(context, params.pixel_count, 0, "instanced aov");
    return read_film(context, film, params.pixel_count);
}

// One sample of the AOV params.aov; `meshes` is the scene of meshes uploaded (its own BVH
// unused), whose layout the instanced trees are assembled in.
inline std::vector<glm::vec4> render_instanced_aov(const cl::Context& context, const DeviceScene& meshes,
                                                   const InstanceBvhParts& parts, const dev::GcRenderParams& params)
{
    switch (meshes.bvh.layout()) {
    case BvhLayout::Binary: return render_instanced_aov_in(context, meshes, assemble_binary(parts), params);
    case BvhLayout::Wide: return render_instanced_aov_in(context, meshes, assemble_wide(parts), params);
    case BvhLayout::Wide8: return render_instanced_aov_in(context, meshes, assemble_wide8(parts), params);
    }
    return {};
}

}  // namespace gc::test
