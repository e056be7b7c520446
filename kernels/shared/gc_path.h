/*
 * gc_path.h — the pieces of the path integrator that are pure functions: choosing and
 * sampling an emitter, and the light density used by MIS. Shared so the host tests and the
 * Vulkan reference make the same decisions as the OpenCL kernels.
 */
#ifndef GC_PATH_H
#define GC_PATH_H

#include "gc_accessors.h"
#include "gc_sampling.h"
#include "gc_scene_buffers.h"

GC_NAMESPACE_BEGIN

/* Luminance weights used for emitter power; make_emitters (host) uses the same. */
GC_FUNC float gc_emitter_luminance(float3 radiance) { return gc_luminance(radiance); }

/* The emitter whose cdf interval contains u: the first i with u < cdf[i]. */
GC_FUNC uint gc_pick_emitter(GC_EMITTERS_PARAM, uint count, float u)
{
    uint lo = 0u;
    uint hi = count - 1u;
    while (lo < hi) {
        const uint mid = (lo + hi) / 2u;
        if (u < GC_EMITTER(mid).cdf) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

/* Emits on the front face (counter-clockwise winding seen from the front, i.e. the side ng
 * points to) unless the material is two-sided. cos_out = cosine between ng and the direction
 * the light leaves in. */
GC_FUNC bool gc_emits_toward(GcMaterial m, float cos_out)
{
    return cos_out > 0.0f || ((m.flags & GC_MATF_TWO_SIDED) != 0u && cos_out < 0.0f);
}

/* Density, per unit solid angle at the receiving point, with which next-event estimation
 * samples a point on an emissive triangle: selection (area * luminance / total power)
 * times uniform area sampling (1 / area), converted by distance^2 / cos. */
GC_FUNC float gc_light_pdf_w(float3 emission, float emitter_power, float dist, float cos_light)
{
    const float pdf_area = gc_emitter_luminance(emission) / emitter_power;
    return pdf_area * dist * dist / fabs(cos_light);
}

/* A fresh path for `sample` of `pixel`: unit throughput, no radiance yet (w, the product of
 * eta^2 over refractions that Russian roulette undoes, starts at 1), and the specular flag,
 * so the camera ray sees emitters with full weight. */
GC_FUNC GcPathState gc_path_start(uint pixel, uint sample)
{
    GcPathState path;
    path.throughput = make_float4(1.0f, 1.0f, 1.0f, 0.0f);
    path.radiance = make_float4(0.0f, 0.0f, 0.0f, 1.0f);
    path.pixel = pixel;
    path.depth = 0u;
    path.flags = GC_PATH_SPECULAR;
    path.sample = sample;
    return path;
}

#if defined(GC_OPENCL)
/* What a finished path adds to its pixel: its radiance, or black when any channel is NaN or
 * infinite (one such sample would poison the pixel's sum forever). */
GC_FUNC float3 gc_film_value(float3 L)
{
    return (isfinite(L.x) && isfinite(L.y) && isfinite(L.z)) ? L : (float3)(0.0f);
}

/* The pixel of slot i of the pass's batch: consecutive pixels from pixel_offset, or the
 * listed ones (GC_RENDER_PIXEL_LIST). A pixel's random numbers are keyed by the pixel itself,
 * so a listed pixel gets the bits it gets in a render of every pixel. */
GC_FUNC uint gc_batch_pixel(GcRenderParams params, __global const uint* pixel_list, uint i)
{
    return (params.flags & GC_RENDER_PIXEL_LIST) != 0u ? pixel_list[params.pixel_offset + i] : params.pixel_offset + i;
}
#endif

GC_NAMESPACE_END

#endif /* GC_PATH_H */
