/*
 * layout_probe.cl — measures the device's view of every shared struct (gc_layout_list.h):
 * out[0] = number of entries, out[1 + i] = sizeof or field offset of entry i. Offsets are
 * pointer differences through a __global struct pointer, because OpenCL C 1.2 has no
 * offsetof guarantee and no _Static_assert. Nothing is dereferenced: `out` only supplies a
 * global address to measure from. The host compares with its own offsetof/sizeof.
 */
#include "gc_types.h"

__kernel void gc_layout_probe(__global uint* out, uint capacity)
{
    if (get_global_id(0) != 0) return;
    __global uchar* base = (__global uchar*)out;
    uint n = 0;
#define GC_PROBE_PUT(value)                           \
    {                                                 \
        if (n + 1u < capacity) out[n + 1u] = (value); \
        ++n;                                          \
    }
#define GC_LAYOUT_SIZE(S) GC_PROBE_PUT((uint)sizeof(S))
#define GC_LAYOUT_FIELD(S, f) \
    GC_PROBE_PUT((uint)((__global uchar*)&((__global S*)base)->f - base))
#include "gc_layout_list.h"
#undef GC_LAYOUT_FIELD
#undef GC_LAYOUT_SIZE
#undef GC_PROBE_PUT
    out[0] = n;
}
