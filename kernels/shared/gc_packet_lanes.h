/*
 * gc_packet_lanes.h — how the CPU path megakernel fills the eight lanes of its camera-ray
 * packets (gc_packet8.h, kernels/megakernel.cl). The host sizes the launch by the same rule,
 * so both include this file.
 *
 * A work-item renders GcRenderParams.pixels_per_item neighbouring pixels of a row (the last
 * item of a batch fewer), each pixel's samples of the pass in sample order, and traces the
 * camera rays of up to eight (pixel, sample) pairs as one packet. With many samples per pass
 * the lanes hold one pixel's samples (pixels_per_item 1); with few, neighbouring pixels fill
 * them: one sample of eight pixels, two of four, three or four of two. Eight rays through
 * eight neighbouring pixels open nearly the same nodes as eight through one pixel, and a pass
 * of one or two samples is what the planner starts every render with and what large images on
 * few cores keep for their first seconds (host/render/pass_planner.h).
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2 and C++20 (gc::dev).
 */
#ifndef GC_PACKET_LANES_H
#define GC_PACKET_LANES_H

#include "gc_platform.h"

/* The packet's width: AVX2's eight floats, and the BVH8's eight children. */
#define GC_PACKET_LANES 8u

/* Fewer rays than this are traced one by one: the packet tests each box and triangle in
 * turn against its lanes, where a single ray tests eight boxes or four triangles at once, so
 * a packet pays only when most lanes hold a ray. Six is the fewest that won on every scene
 * measured (docs/decisions/camera-ray-packets.md). */
#define GC_PACKET_MIN_LANES 6u

GC_NAMESPACE_BEGIN

/* Pixels per megakernel work-item for passes of `samples_in_pass` samples, where the program
 * traces camera packets: as many as fill the lanes with at least GC_PACKET_MIN_LANES rays,
 * else 1 (then a pixel's samples are split into packets of up to eight, or, below six, traced
 * one by one). */
GC_FUNC uint gc_megakernel_pixels_per_item(uint samples_in_pass)
{
    if (samples_in_pass == 0u || samples_in_pass >= GC_PACKET_MIN_LANES) return 1u;
    const uint pixels = GC_PACKET_LANES / samples_in_pass;
    return pixels * samples_in_pass >= GC_PACKET_MIN_LANES ? pixels : 1u;
}

GC_NAMESPACE_END

#endif /* GC_PACKET_LANES_H */
