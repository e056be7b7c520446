#include "host/render/device_bvh.h"

#include "host/bvh/widen.h"

namespace gc {
BvhLayout bvh_layout_for(const cl::DeviceInfo& device, std::optional<BvhLayout> chosen)
{
    if (chosen) return *chosen;
    // A GPU runs a warp of rays in lock step, and a float4 there is four scalar instructions,
    // so the BVH2 is faster there. CPUs gain from the wide tests: the BVH4 over the BVH2, and
    // the BVH8 over the BVH4 where the SIMD unit holds eight floats (AVX). Figures:
    // docs/decisions/gpu-bvh-layout.md. PoCL reports that width as the preferred float vector
    // width (16 on AVX-512, 8 on AVX2, 4 on SSE).
    if (device.is_gpu) return BvhLayout::Binary;
    return device.preferred_vector_width_float >= 8 ? BvhLayout::Wide8 : BvhLayout::Wide;
}

std::string program_options(BvhLayout layout)
{
    switch (layout) {
    case BvhLayout::Binary: return "";
    case BvhLayout::Wide: return "-D GC_BVH_WIDE";
    case BvhLayout::Wide8: return "-D GC_BVH_WIDE -D GC_BVH_WIDE8";
    }
    return "";
}

const char* layout_name(BvhLayout layout)
{
    switch (layout) {
    case BvhLayout::Binary: return "BVH2";
    case BvhLayout::Wide: return "BVH4";
    case BvhLayout::Wide8: return "BVH8";
    }
    return "BVH2";
}

DeviceBvh DeviceBvh::upload(const cl::Context& context, const FlatBvh& bvh, BvhLayout layout)
{
    DeviceBvh d;
    d.m_layout = layout;
    // The wide layouts are built here and owned by the DeviceBvh, so CPUs can trace them in
    // place; a GPU copies them (over_host falls back) and the host arrays are dropped.
    if (layout == BvhLayout::Wide) {
        auto wide = std::make_shared<const WideBvh>(widen(bvh));
        d.m_wide_nodes = cl::Buffer<dev::GcBvh4Node>::over_host(context, wide->nodes, "bvh4 nodes");
        d.m_wide_blocks = cl::Buffer<dev::GcTriangle4>::over_host(context, wide->blocks, "bvh4 triangle blocks");
        if (context.device().is_cpu) d.m_host_arrays = std::move(wide);
    } else if (layout == BvhLayout::Wide8) {
        auto wide = std::make_shared<const Wide8Bvh>(widen8(bvh));
        d.m_wide8_nodes = cl::Buffer<dev::GcBvh8Node>::over_host(context, wide->nodes, "bvh8 nodes");
        d.m_wide_blocks = cl::Buffer<dev::GcTriangle4>::over_host(context, wide->blocks, "bvh8 triangle blocks");
        if (context.device().is_cpu) d.m_host_arrays = std::move(wide);
    } else {
        d.m_nodes = cl::read_only_buffer(context, bvh.nodes, "bvh nodes");
        d.m_triangles = cl::read_only_buffer(context, bvh.triangles, "bvh triangles");
    }
    return d;
}

DeviceBvh DeviceBvh::upload_instanced(const cl::Context& context, const InstanceBvhParts& parts, BvhLayout layout,
                                      DeviceInstanceLevel& top)
{
    DeviceBvh d;
    d.m_layout = layout;
    auto upload_top = [&](const auto& bvh) {
        top.tlas = cl::read_only_buffer(context, bvh.tlas, "instance tlas");
        top.instances = cl::read_only_buffer(context, bvh.instances, "instances");
    };
    if (layout == BvhLayout::Wide) {
        const InstancedBvh4 bvh = assemble_wide(parts);
        d.m_wide_nodes = cl::read_only_buffer(context, bvh.nodes, "mesh bvh4 nodes");
        d.m_wide_blocks = cl::read_only_buffer(context, bvh.tris, "mesh bvh4 triangle blocks");
        upload_top(bvh);
    } else if (layout == BvhLayout::Wide8) {
        const InstancedBvh8 bvh = assemble_wide8(parts);
        d.m_wide8_nodes = cl::read_only_buffer(context, bvh.nodes, "mesh bvh8 nodes");
        d.m_wide_blocks = cl::read_only_buffer(context, bvh.tris, "mesh bvh8 triangle blocks");
        upload_top(bvh);
    } else {
        const InstancedBvh bvh = assemble_binary(parts);
        d.m_nodes = cl::read_only_buffer(context, bvh.nodes, "mesh bvh nodes");
        d.m_triangles = cl::read_only_buffer(context, bvh.tris, "mesh bvh triangles");
        upload_top(bvh);
    }
    return d;
}

cl_mem DeviceBvh::nodes() const
{
    switch (m_layout) {
    case BvhLayout::Binary: return m_nodes.mem();
    case BvhLayout::Wide: return m_wide_nodes.mem();
    case BvhLayout::Wide8: return m_wide8_nodes.mem();
    }
    return m_nodes.mem();
}

cl_mem DeviceBvh::triangles() const
{
    return m_layout == BvhLayout::Binary ? m_triangles.mem() : m_wide_blocks.mem();
}

std::uint64_t DeviceBvh::bytes() const
{
    return m_nodes.bytes() + m_triangles.bytes() + m_wide_nodes.bytes() + m_wide8_nodes.bytes() + m_wide_blocks.bytes();
}

}  // namespace gc
