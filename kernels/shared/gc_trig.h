/*
 * gc_trig.h — sine and cosine for the samplers, and the arc tangent of the environment
 * map's lookup, as short polynomials instead of the platform's functions.
 *
 * Why: every angle a sampler needs is either in [-pi/4, pi/4] already (the concentric disk
 * map) or a fraction of a turn (phi = 2 pi u), which reduces to that interval exactly. The
 * platform functions cannot know that: PoCL's sin/cos run a general argument reduction on
 * every call (__pocl_argReductionS), a visible share of a CPU path sample
 * (docs/decisions/pocl-hot-spots.md). And they differ between devices by an ulp or two
 * (OpenCL allows 4 ulp), so the same path would take slightly different directions on PoCL and
 * on NVIDIA. These use + and * only, with contraction off (gc_platform.h), so every device and
 * the host compute the same bits.
 *
 * Accuracy on [-pi/4, pi/4] (tests/bsdf/trig_test.cpp measures it against double): sine within
 * 0.77 ulp, cosine within 1.23 ulp. The coefficients are a minimax fit (Lawson's iteration on
 * relative error) made for this file: sin x = x + x^3 P(x^2), cos x = 1 - x^2/2 + x^4 Q(x^2),
 * P and Q of degree 2.
 *
 * The arc tangent reduces its argument to [0, 1] (swapping y and x), then to
 * |z| <= tan(pi/8) (atan t = pi/4 + atan((t - 1) / (t + 1))), then halves the angle once
 * (atan z = 2 atan(z / (1 + sqrt(1 + z^2))), |z| <= 0.199) and sums the Taylor series to z^11
 * (next term below 4e-10 of the result): + * / and sqrt only, all correctly rounded, so it
 * too gives the same bits everywhere; trig_test.cpp measures it.
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

/* atan t for t in [0, 1]. */
GC_FUNC float gc_atan_unit(float t)
{
    float base = 0.0f;
    if (t > 0.414213562f) {
        t = (t - 1.0f) / (t + 1.0f);
        base = 0.785398163f; /* pi / 4 */
    }
    const float z = t / (1.0f + sqrt(1.0f + t * t));
    const float z2 = z * z;
    const float series =
        z * (1.0f + z2 * (-0.333333333f + z2 * (0.2f + z2 * (-0.142857143f + z2 * (0.111111111f + z2 * -0.0909090909f)))));
    return base + 2.0f * series;
}

/* The angle of (x, y) in (-pi, pi], as atan2(y, x); 0 for (0, 0). */
GC_FUNC float gc_atan2(float y, float x)
{
    const float ax = fabs(x);
    const float ay = fabs(y);
    const float hi = fmax(ax, ay);
    if (!(hi > 0.0f)) return 0.0f;
    float a = gc_atan_unit(fmin(ax, ay) / hi);
    if (ay > ax) a = 1.57079633f - a; /* pi / 2 */
    if (x < 0.0f) a = GC_PI - a;
    return y < 0.0f ? -a : a;
}

GC_NAMESPACE_END

#endif /* GC_TRIG_H */
