// The BVH as one device reads it: BVH2 (GcBvhNode + GcTriangle) on GPUs; on CPUs BVH8
// (GcBvh8Node, gc_traverse8.h) where the SIMD unit holds eight floats, else BVH4 (GcBvh4Node,
// gc_traverse4.h), with GcTriangle4 leaves (host/bvh/widen.h): one ray tests eight or four
// boxes, then four triangles, with SIMD instructions. All give the same hits, bit for bit,
// so the choice is about speed only. Programs that trace rays must be built with
// program_options(layout), which selects the matching traversal in the kernels.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "host/bvh/flatten.h"
#include "host/bvh/instance_bvh.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"

namespace gc {

enum class BvhLayout { Binary, Wide, Wide8 };

// `chosen` when set (A/B benchmarks, tests), else BVH8 or BVH4 on CPUs, BVH2 on GPUs.
BvhLayout bvh_layout_for(const cl::DeviceInfo& device, std::optional<BvhLayout> chosen = std::nullopt);

// "" for the BVH2, "-D GC_BVH_WIDE" for the BVH4, "-D GC_BVH_WIDE -D GC_BVH_WIDE8" for the BVH8.
std::string program_options(BvhLayout layout);

const char* layout_name(BvhLayout layout);  // "BVH2", "BVH4" or "BVH8"

// The top level of an instanced scene's two-level BVH on a device (gc_traverse_instances.h's
// GC_INSTANCE_PARAMS): a BVH2 over the instances, and the instances in its leaf order.
struct DeviceInstanceLevel {
    cl::Buffer<dev::GcBvhNode> tlas;
    cl::Buffer<dev::GcInstance> instances;
};

class DeviceBvh {
public:
    DeviceBvh() = default;
    // Uploads `bvh` in `layout` (collapsing it to a BVH4 first where asked).
    static DeviceBvh upload(const cl::Context& context, const FlatBvh& bvh, BvhLayout layout);
    // Uploads an instanced scene's meshes' trees in `layout` as the DeviceBvh the bottom
    // traversal reads, and its top level into `top`.
    static DeviceBvh upload_instanced(const cl::Context& context, const InstanceBvhParts& parts, BvhLayout layout,
                                      DeviceInstanceLevel& top);

    BvhLayout layout() const { return m_layout; }
    // The two buffers the traversal kernels take, in either layout.
    cl_mem nodes() const;
    cl_mem triangles() const;
    std::uint64_t bytes() const;

private:
    BvhLayout m_layout = BvhLayout::Binary;
    // The wide BVH's host arrays, which CPU devices read in place (cl::Buffer::over_host).
    // Declared before the buffers so that they are released first.
    std::shared_ptr<const void> m_host_arrays;
    cl::Buffer<dev::GcBvhNode> m_nodes;
    cl::Buffer<dev::GcTriangle> m_triangles;
    cl::Buffer<dev::GcBvh4Node> m_wide_nodes;
    cl::Buffer<dev::GcTriangle4> m_wide_blocks;
    cl::Buffer<dev::GcBvh8Node> m_wide8_nodes;
};

}  // namespace gc
