/*
 * gc_pow.h — x^y for x >= 0, from a base-2 logarithm and exponential of our own.
 *
 * Why: OpenCL allows pow 16 ulp and GLSL leaves it to the driver, so the Phong lobe's value
 * and its sampled cosine (gc_sampling.h, gc_bsdf.h) differed between devices. These use +, *,
 * one correctly rounded division, floor and bit operations only, with contraction off
 * (gc_platform.h): the same bits on every device and on the host.
 *
 * log2: x = m 2^e with m in [sqrt(1/2), sqrt(2)); log2 m = (2 / ln 2) atanh s with
 * s = (m - 1) / (m + 1), |s| <= 0.1716, and the atanh series to s^13 (next term < 2e-12).
 * exp2: y = n + f with n = round(y), |f| <= 1/2; 2^f = e^(f ln 2) by its Taylor series to the
 * 8th power (next term < 3e-10); 2^n is built in the exponent bits, in two steps outside the
 * normal range.
 * tests/bsdf/pow_test.cpp measures both and pow against double precision.
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2, C++20 (gc::dev) and GLSL 4.50.
 */
#ifndef GC_POW_H
#define GC_POW_H

#include "gc_platform.h"

GC_NAMESPACE_BEGIN

/* log2 x for finite x > 0 (denormals included); -infinity for 0. */
GC_FUNC float gc_log2(float x)
{
    if (!(x > 0.0f)) return -gc_as_float(0x7f800000u);
    float e = 0.0f;
    if (x < 1.17549435e-38f) { /* a denormal: scale it into the normal range first */
        x = x * 8388608.0f;    /* 2^23 */
        e = -23.0f;
    }
    /* Adding 1 - sqrt(1/2) in the bits (0x3f800000 - 0x3f3504f3) carries into the exponent
     * exactly when the mantissa is at least sqrt(2)'s, so `biased` is e + 127 for the split
     * with m in [sqrt(1/2), sqrt(2)). Unsigned throughout: x > 0 keeps the top bit clear. */
    const uint bits = gc_as_uint(x);
    const uint biased = (bits + 0x004afb0du) >> 23u;
    const float m = gc_as_float(bits - (biased << 23u) + 0x3f800000u);
    e = e + (gc_float(biased) - 127.0f);
    const float s = (m - 1.0f) / (m + 1.0f);
    const float s2 = s * s;
    /* ln m = 2 atanh s = 2 (s + s^3/3 + s^5/5 + ...) */
    const float ln_m =
        s * (2.0f + s2 * (0.666666667f + s2 * (0.4f + s2 * (0.285714286f + s2 * (0.222222222f + s2 * (0.181818182f + s2 * 0.153846154f))))));
    return e + ln_m * 1.44269504f; /* 1 / ln 2 */
}

/* 2^y; 0 below 2^-149, +infinity above 2^128. */
GC_FUNC float gc_exp2(float y)
{
    if (!(y > -150.0f)) return 0.0f;
    if (y >= 128.0f) return gc_as_float(0x7f800000u);
    const float n = floor(y + 0.5f);
    const float z = (y - n) * 0.693147181f; /* ln 2 */
    const float p =
        1.0f + z * (1.0f + z * (0.5f + z * (0.166666667f + z * (0.0416666667f + z * (0.00833333333f + z * (0.00138888889f + z * (1.98412698e-04f + z * 2.48015873e-05f)))))));
    const int k = gc_int(n);
    /* y in [127.5, 128) rounds to n = 128, one past the largest normal exponent. */
    if (k > 127) return (p * gc_as_float(gc_uint(k + 126) << 23u)) * 2.0f;
    if (k >= -126) return p * gc_as_float(gc_uint(k + 127) << 23u);
    /* Below the normal range: two steps, so each power of two is a normal float. */
    return (p * gc_as_float(gc_uint(k + 127 + 64) << 23u)) * 5.42101086e-20f; /* 2^-64 */
}

/* x^y for x >= 0: 0^y is 0 for y > 0 and 1 for y == 0, as pow gives. */
GC_FUNC float gc_pow(float x, float y)
{
    if (y == 0.0f) return 1.0f;
    if (!(x > 0.0f)) return 0.0f;
    return gc_exp2(y * gc_log2(x));
}

GC_NAMESPACE_END

#endif /* GC_POW_H */
