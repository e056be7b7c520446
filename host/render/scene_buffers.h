// The host half of kernels/shared/gc_scene_buffers.h: DeviceScene's kernel-argument groups,
// generated from the same list of scene buffers as the kernels' parameter lists, so a group's
// buffers are passed in the order and number its GC_*_PARAMS declares them.
#pragma once

#include <tuple>

#include "gc_scene_buffers.h"
#include "host/cl/buffer.h"
#include "host/cl/cl_api.h"

namespace gc::scene_buffers {

// One list entry as a set_args group of one: a Buffer by reference (its name labels errors),
// a raw cl_mem (DeviceBvh's layout-dependent buffers) by value.
template <class T>
auto arg(const cl::Buffer<T>& buffer)
{
    return std::tie(buffer);
}
inline auto arg(cl_mem mem) { return std::make_tuple(mem); }

}  // namespace gc::scene_buffers

// Inside a DeviceScene member function: the tuple of `group`'s buffers (BVH, TRACE, ALPHA,
// SHADE, LIGHTS or SCENE), each row's DeviceScene expression in list order.
#define GC_DEVICE_SCENE_ARG(g, name, type, host, bvh, alpha, shade, lights) \
    GC_SCENE_PICK(g, bvh, alpha, shade, lights, GC_DEVICE_SCENE_ARG_)(host)
#define GC_DEVICE_SCENE_ARG_0(host)
#define GC_DEVICE_SCENE_ARG_1(host) , ::gc::scene_buffers::arg(host)
#define GC_DEVICE_SCENE_ARG_F(host) GC_DEVICE_SCENE_ARG_1(host)
#define GC_DEVICE_SCENE_ARGS(group) std::tuple_cat(std::tuple<>() GC_SCENE_BUFFERS(GC_DEVICE_SCENE_ARG, group))
