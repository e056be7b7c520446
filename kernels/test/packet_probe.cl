/*
 * packet_probe.cl — what explicit SIMD across paths would gain on a device, and whether it
 * keeps the bits. One Lambert path vertex, shaped like gc_path_vertex.h's diffuse case but
 * self-contained (next-event estimation to a fixed quad light with an MIS weight, then a
 * cosine-weighted direction in world space; random numbers hashed from the vertex index; no
 * float3), is compiled three ways from one source (packet_probe_vertex.h):
 *
 *   packet_probe_x1   one vertex per work-item, as every kernel of the renderer works today
 *   packet_probe_x8   eight vertices per work-item in float8 lanes
 *   packet_probe_x16  sixteen per work-item in float16 lanes
 *
 * PoCL runs one work-item after another on a core and does not vectorise our kernels across
 * them (README, Performance), so on a CPU the lanes are the only SIMD the shading can get;
 * GPUs already run work-items in lock step. geocold-bench times the three per device;
 * DevicePacketProbe checks that all three give the same bits (IEEE operations lane by lane).
 * Inputs and outputs are structure-of-arrays, one float per vertex and component.
 */
#define GC_PROBE_LANES 1
#include "test/packet_probe_vertex.h"
#undef GC_PROBE_LANES

#define GC_PROBE_LANES 8
#include "test/packet_probe_vertex.h"
#undef GC_PROBE_LANES

#define GC_PROBE_LANES 16
#include "test/packet_probe_vertex.h"
#undef GC_PROBE_LANES
