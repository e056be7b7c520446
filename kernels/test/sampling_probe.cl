/*
 * sampling_probe.cl — evaluates the samplers' trigonometry (gc_trig.h) and the cosine-weighted
 * hemisphere warp for a list of inputs, so tests can check that every device computes the
 * host's bits: the directions a path takes must not depend on the device's sin/cos.
 */
#include "gc_sampling.h"

__kernel void sampling_probe(__global const float2* inputs, __global float4* turns_out,
                             __global float4* hemisphere_out, const uint count)
{
    const uint i = get_global_id(0);
    if (i >= count) return;
    const float2 u = inputs[i];
    turns_out[i] = (float4)(gc_cos_sin_turns(u.x), gc_cos_sin_quarter((2.0f * u.y - 1.0f) * (0.25f * GC_PI)));
    hemisphere_out[i] = (float4)(gc_sample_cosine_hemisphere(u.x, u.y), 0.0f);
}
