#include "host/render/device_bvh.h"

#include <cstdlib>

#include "host/bvh/widen.h"
#include "host/util/error.h"

namespace gc {
BvhLayout bvh_layout_for(const cl::DeviceInfo& device)
{
    if (const char* env = std::getenv("GEOCOLD_BVH_WIDTH"); env && *env) {
        const std::string width(env);
        if (width != "2" && width != "4")
            throw UsageError("GEOCOLD_BVH_WIDTH must be 2 or 4, not '" + width + "'");
        return width == "4" ? BvhLayout::Wide : BvhLayout::Binary;
    }
    // A GPU runs a warp of rays in lock step, and a float4 there is four scalar instructions:
    // the BVH2 measured faster. CPUs gain from the 4-wide tests (figures in the issue notes).
    return device.is_gpu ? BvhLayout::Binary : BvhLayout::Wide;
}

std::string program_options(BvhLayout layout)
{
    return layout == BvhLayout::Wide ? "-D GC_BVH_WIDE" : "";
}

const char* layout_name(BvhLayout layout)
{
    return layout == BvhLayout::Wide ? "BVH4" : "BVH2";
}

DeviceBvh DeviceBvh::upload(const cl::Context& context, const FlatBvh& bvh, BvhLayout layout)
{
    DeviceBvh d;
    d.m_layout = layout;
    if (layout == BvhLayout::Wide) {
        const WideBvh wide = widen(bvh);
        d.m_wide_nodes = cl::read_only_buffer(context, wide.nodes, "bvh4 nodes");
        d.m_wide_blocks = cl::read_only_buffer(context, wide.blocks, "bvh4 triangle blocks");
    } else {
        d.m_nodes = cl::read_only_buffer(context, bvh.nodes, "bvh nodes");
        d.m_triangles = cl::read_only_buffer(context, bvh.triangles, "bvh triangles");
    }
    return d;
}

cl_mem DeviceBvh::nodes() const
{
    return m_layout == BvhLayout::Wide ? m_wide_nodes.mem() : m_nodes.mem();
}

cl_mem DeviceBvh::triangles() const
{
    return m_layout == BvhLayout::Wide ? m_wide_blocks.mem() : m_triangles.mem();
}

std::uint64_t DeviceBvh::bytes() const
{
    return m_nodes.bytes() + m_triangles.bytes() + m_wide_nodes.bytes() + m_wide_blocks.bytes();
}

}  // namespace gc
