/*
 * adjoint.cl — the adjoint of the path integrator (path replay backpropagation): gradients of
 * a loss of the image with respect to the scene's parameters. One work-item per pixel and run
 * of samples (all of the pixel's on CPUs, one on GPUs: the host's choice); for each sample it
 *   1. learns the sample's radiance L: from the path states of the wavefront pass the host ran
 *      just before over the same pixels and samples (`primal`, on GPUs: the same bits, traced
 *      faster), or by tracing the path itself as megakernel.cl does (the same calls with the
 *      same random-number keys, gc_shade_vertex);
 *   2. traces it again, and at each vertex gc_vertex_adjoint adds the derivative of what the
 *      vertex contributed, weighted by d loss / d L, to the parameters' slots.
 * The second pass needs only L and the running sum, not the vertices of the first, so memory
 * does not grow with path depth. The loss's gradient image is d loss / d (pixel mean); each
 * sample's share is that over the pass's samples (the host divides before upload).
 * A sample whose radiance is not finite is dropped, as the film drops it.
 */
#include "gc_traverse.h"
#include "gc_path_adjoint.h"
#include "gc_camera.h"
#include "gc_rng.h"

/* Traces the path of (pixel, sample) from `ray` to its end; with `adjoint`, adds its
 * derivatives given the total radiance L and d loss / d L. Returns the radiance. */
static float3 gc_adjoint_path(const GcRenderParams params, GC_SCENE_PARAMS, GcGradTarget g, const uint pixel,
                              const uint sample, const GcRay camera_ray, const bool adjoint, const float3 L,
                              const float3 delta)
{
    GcRay ray = camera_ray;
    GcPathState path = gc_path_start(pixel, sample);
    for (;;) {
        const GcHit hit = gc_trace_closest(GC_BVH_ARGS, ray);
        const GcPathState before = path;
        const GcVertexResult res = gc_shade_vertex(GC_SHADE_ARGS, params, path, ray, hit);
        path = res.path;
        bool visible = false;
        if ((res.flags & GC_VERTEX_SHADOW) != 0u && !gc_trace_any(GC_BVH_ARGS, res.shadow.ray)) {
            visible = true;
            path.radiance += res.shadow.contribution;
        }
        if (adjoint)
            gc_vertex_adjoint(GC_SHADE_ARGS, params, g, before, ray, hit, res, visible, L - GC_XYZ(path.radiance),
                              delta);
        if ((res.flags & GC_VERTEX_CONTINUE) == 0u) break;
        ray = res.next;
    }
    return GC_XYZ(path.radiance);
}

/* Samples [first, end) of the pass at the batch's pixel `slot`: each sample's L (from `primal`,
 * laid out as generate.cl lays out a pass's paths, where given), then its derivatives. */
static void gc_adjoint_pixel(const GcRenderParams params, GC_SCENE_PARAMS, GcGradTarget g, const uint slot,
                             const float3 delta, const uint first, const uint end,
                             __global const GcPathState* primal, const bool primal_given)
{
    const uint pixel = params.pixel_offset + slot;
    for (uint k = first; k < end; ++k) {
        const uint sample = params.sample_index + k;
        const float4 jitter = gc_sample4(params, pixel, sample, GC_RNG_BLOCK_CAMERA);
        const GcRay ray = gc_camera_sample(params.camera, params.width, params.height, pixel % params.width,
                                           pixel / params.width, jitter);
        const float3 L = primal_given ? GC_XYZ(primal[slot * params.samples_in_pass + k].radiance)
                                      : gc_adjoint_path(params, GC_SCENE_ARGS, g, pixel, sample, ray, false,
                                                        (float3)(0.0f), delta);
        if (!(isfinite(L.x) && isfinite(L.y) && isfinite(L.z))) continue;
        gc_adjoint_path(params, GC_SCENE_ARGS, g, pixel, sample, ray, true, L, delta);
    }
}

__kernel void path_adjoint(const GcRenderParams params,
                           GC_SCENE_PARAMS,
                           __global const float4* loss_grad,
                           __global ulong* slots,
                           __global uint* max_bits,
                           __global const uint* view_slots,
                           __global const uint* wanted,
                           __global const GcPathState* primal,
                           const uint primal_given,
                           const float scale,
                           const uint env_slot,
                           const uint slot_count,
                           const uint view_count,
                           const uint samples_per_item)
{
    GcGradTarget g;
    g.slots = slots;
    g.max_bits = max_bits;
    g.view_slots = view_slots;
    g.scale = scale;
    g.wanted = wanted;
    g.env_slot = env_slot;
    g.texel_slot = env_slot + GC_GRAD_ENV_SLOTS;
    g.slot_count = slot_count;
    g.view_count = view_count;
    /* Work-item i takes pixel i mod pixel_count and the (i / pixel_count)-th run of
     * samples_per_item samples there: neighbouring items trace neighbouring pixels. */
    const uint item = get_global_id(0);
    const uint first = (item / params.pixel_count) * samples_per_item;
    if (first < params.samples_in_pass) {
        const uint slot = item % params.pixel_count;
        const float3 delta = loss_grad[params.pixel_offset + slot].xyz;
        if (delta.x != 0.0f || delta.y != 0.0f || delta.z != 0.0f)
            gc_adjoint_pixel(params, GC_SCENE_ARGS, g, slot, delta, first,
                             min(first + samples_per_item, params.samples_in_pass), primal, primal_given != 0u);
    }
}
