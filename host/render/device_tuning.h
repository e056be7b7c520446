// How the renderer drives a device: choices that change speed, never the image. Each one has
// a per-device default, and each can be fixed here instead, for A/B benchmarks and for the
// tests that check every choice gives the same bits. Libraries take these as a value; only the
// front ends (host/app, tools/bench) fill them in, from the environment or the command line.
#pragma once

#include <cstdint>
#include <optional>

#include "host/render/device_bvh.h"

namespace gc {

// The path integrator's two forms, built from the same shared code (renderer.h).
enum class PathKernelForm {
    Auto,        // megakernel on CPUs, wavefront on GPUs (path_megakernel_for)
    Wavefront,   // kernels/wavefront.cl: one launch per stage and bounce
    Megakernel,  // kernels/megakernel.cl: one work-item runs a whole path
};

// Which kernel code a program is compiled with (kernel_features.h).
enum class KernelFeatureSet {
    Scene,  // only the features the scene uses: smaller programs, faster PoCL builds
    All,    // every feature: the full programs, to check the bits agree with Scene's
};

struct DeviceTuning {
    // The BVH layout traversed. nullopt: bvh_layout_for's choice (BVH8 or BVH4 on CPUs by
    // SIMD width, BVH2 on GPUs), the fastest on each (docs/decisions/gpu-bvh-layout.md).
    std::optional<BvhLayout> bvh_layout;
    PathKernelForm path_kernel = PathKernelForm::Auto;
    KernelFeatureSet kernel_features = KernelFeatureSet::Scene;
    // Wavefront launches after the first bounce: this many work-items per compute unit on
    // every batch (0: one per queue entry) instead of sizing each launch from the last batch
    // (GPUs) or from the lengths read back (CPUs). Exists for A/B runs of the launch widths and
    // for tests, which use 1 so that the kernels' loops over uncovered entries run everywhere.
    std::optional<std::uint32_t> wavefront_items_per_unit;
    // Wavefront: whether the host reads each bounce's queue lengths back and launches over the
    // live paths only. nullopt: yes on CPUs, where the read is nearly free and an idle
    // work-item is not, no on GPUs, where a blocking read per bounce stalls the queue.
    std::optional<bool> wavefront_sync_counts;
};

}  // namespace gc
