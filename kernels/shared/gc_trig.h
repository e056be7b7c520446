/*
 * gc_trig.h — sine and cosine for the samplers, and atan2 for the environment map, as short
 * polynomials instead of the platform's functions.
 *
 * Why: every angle a sampler needs is either in [-pi/4, pi/4] already (the concentric disk
 * map) or a fraction of a turn (phi = 2 pi u), which reduces to that interval exactly. The
 * platform functions cannot know that: PoCL's sin/cos run a general argument reduction on
 * every call (__pocl_argReductionS), which perf put at 5 % of the Cornell path megakernel,
 * plus 8 % in the sampler around it. And they differ between devices by an ulp or two
 * (OpenCL allows 4 ulp), so the same path took slightly different directions on PoCL and on
 * NVIDIA. These use + and * only, with contraction off (gc_platform.h), so every device and
 * the host compute the same bits.
 *
 * Accuracy on [-pi/4, pi/4] (tests/bsdf/trig_test.cpp measures it against double): sine within
 * 0.77 ulp, cosine within 1.23 ulp. The coefficients are a minimax fit (Lawson's iteration on
 * relative error) made for this file: sin x = x + x^3 P(x^2), cos x = 1 - x^2/2 + x^4 Q(x^2),
 * P and Q of degree 2.
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2, C++20 (gc::dev) and GLSL 4.50.
 */
#ifndef GC_TRIG_H
#define GC_TRIG_H

#include "gc_platform.h"

GC_NAMESPACE_BEGIN

/* (cos x, sin x) for |x| <= pi/4. */
GC_FUNC float2 gc_cos_sin_quarter(float x)
{
    const float z = x * x;
    const float s = x + x * z * (-0.166666552f + z * (0.00833216123f + z * -0.000195153087f));
    const float c = 1.0f - 0.5f * z + z * z * (0.0416666456f + z * (-0.00138873165f + z * 2.44331768e-05f));
    return make_float2(c, s);
}

/* (cos 2 pi t, sin 2 pi t) for t in [0, 1]: the nearest quarter turn q / 4 is taken off
 * exactly (t - q / 4 has at most t's bits), the rest is within an eighth of a turn, and the
 * quarter turns are exact swaps and sign changes. */
GC_FUNC float2 gc_cos_sin_turns(float t)
{
    const float q = floor(4.0f * t + 0.5f);
    const float2 cs = gc_cos_sin_quarter((t - 0.25f * q) * (2.0f * GC_PI));
    const uint quadrant = gc_uint(q) & 3u;
    if (quadrant == 0u) return cs;
    if (quadrant == 1u) return make_float2(-cs.y, cs.x);
    if (quadrant == 2u) return make_float2(-cs.x, -cs.y);
    return make_float2(cs.y, -cs.x);
}

/* atan2(y, x) in [-pi, pi], for the environment map's lat-long lookup (gc_lights.h), from +, *
 * and one division (correctly rounded on every device: the OpenCL programs ask for it, GLSL
 * and C++ have it), so the OpenCL kernels and the Vulkan reference pick the same texel and
 * density: the platforms' atan2 and acos differ by an ulp or two, and near texel edges that
 * was a different texel. The smaller magnitude over the larger, a in [0, 1], is reduced to
 * |a| <= tan(pi/8) by atan(a) = pi/4 + atan((a - 1) / (a + 1)); there a + a^3 P(a^2) is
 * Cephes' atanf polynomial (relative error below 2e-7; tests/bsdf/trig_test.cpp measures the
 * whole function against double). Then atan(lo/hi) becomes the angle by the octant. Signed
 * zeros are not told apart: atan2(+-0, x) is 0 for x >= 0 and pi for x < 0. */
GC_FUNC float gc_atan2(float y, float x)
{
    const float ax = fabs(x);
    const float ay = fabs(y);
    const float hi = fmax(ax, ay);
    if (!(hi > 0.0f)) return 0.0f;
    float a = fmin(ax, ay) / hi;
    float r = 0.0f;
    if (a > 0.414213562f) {
        a = (a - 1.0f) / (a + 1.0f);
        r = 0.25f * GC_PI;
    }
    const float z = a * a;
    r += a + a * z * (-0.333329491539f + z * (0.199777106478f + z * (-0.138776856032f + z * 0.0805374449538f)));
    if (ay > ax) r = 0.5f * GC_PI - r;
    if (x < 0.0f) r = GC_PI - r;
    return y < 0.0f ? -r : r;
}

GC_NAMESPACE_END

#endif /* GC_TRIG_H */
