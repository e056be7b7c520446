// Four-float vectors for the BVH builder's inner loops (binning and partitioning): one box
// corner per register, so growing a box is one min and one max instead of six scalar ops.
// SSE2 (every x86-64) where available, plain loops elsewhere; both give the same bits,
// because min, max, add, sub, mul and truncation are exact IEEE operations per lane.
#pragma once

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gc::simd {

#if defined(__SSE2__)

struct Vec4 {
    __m128 v;
};

inline Vec4 load(const float* p) { return {_mm_load_ps(p)}; } // p 16-byte aligned
inline void store(float* p, Vec4 a) { _mm_store_ps(p, a.v); }
inline Vec4 splat(float x) { return {_mm_set1_ps(x)}; }
inline Vec4 make(float x, float y, float z, float w) { return {_mm_setr_ps(x, y, z, w)}; }
inline Vec4 operator+(Vec4 a, Vec4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline Vec4 operator-(Vec4 a, Vec4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline Vec4 operator*(Vec4 a, Vec4 b) { return {_mm_mul_ps(a.v, b.v)}; }
// Inputs are finite (or +-inf for empty boxes), so the NaN rules of minps/maxps never apply.
inline Vec4 min(Vec4 a, Vec4 b) { return {_mm_min_ps(a.v, b.v)}; }
inline Vec4 max(Vec4 a, Vec4 b) { return {_mm_max_ps(a.v, b.v)}; }
// Lanes x, y, z kept, w zeroed: the builder keeps a triangle index in the w lane of its
// boxes, whose bits must not reach arithmetic (as a float it is denormal or NaN).
inline Vec4 xyz(Vec4 a)
{
    const __m128i mask = _mm_setr_epi32(-1, -1, -1, 0);
    return {_mm_and_ps(a.v, _mm_castsi128_ps(mask))};
}
// Truncation towards zero of each lane; lanes must be in int range.
inline void truncate(Vec4 a, std::int32_t* out) // out 16-byte aligned, 4 entries
{
    _mm_store_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(a.v));
}
// The x, y and z lanes of three vectors, regrouped: x = (a.x, b.x, c.x, 0), and so on.
inline void transpose3(Vec4 a, Vec4 b, Vec4 c, Vec4& x, Vec4& y, Vec4& z)
{
    const __m128 zero = _mm_setzero_ps();
    const __m128 ab_lo = _mm_unpacklo_ps(a.v, b.v); // a.x b.x a.y b.y
    const __m128 ab_hi = _mm_unpackhi_ps(a.v, b.v); // a.z b.z a.w b.w
    const __m128 c_lo = _mm_unpacklo_ps(c.v, zero); // c.x 0 c.y 0
    const __m128 c_hi = _mm_unpackhi_ps(c.v, zero); // c.z 0 c.w 0
    x.v = _mm_movelh_ps(ab_lo, c_lo);
    y.v = _mm_movehl_ps(c_lo, ab_lo);
    z.v = _mm_movelh_ps(ab_hi, c_hi);
}

#else

struct Vec4 {
    float v[4];
};

inline Vec4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
inline void store(float* p, Vec4 a)
{
    for (int i = 0; i < 4; ++i) p[i] = a.v[i];
}
inline Vec4 splat(float x) { return {{x, x, x, x}}; }
inline Vec4 make(float x, float y, float z, float w) { return {{x, y, z, w}}; }
#define GC_SIMD4_LANEWISE(op, expr)                                                                                    \
    inline Vec4 op(Vec4 a, Vec4 b)                                                                                     \
    {                                                                                                                  \
        Vec4 r;                                                                                                        \
        for (int i = 0; i < 4; ++i) r.v[i] = (expr);                                                                   \
        return r;                                                                                                      \
    }
GC_SIMD4_LANEWISE(operator+, a.v[i] + b.v[i])
GC_SIMD4_LANEWISE(operator-, a.v[i] - b.v[i])
GC_SIMD4_LANEWISE(operator*, a.v[i] * b.v[i])
// As minps/maxps: the second operand when the lanes compare equal (+0 vs -0).
GC_SIMD4_LANEWISE(min, a.v[i] < b.v[i] ? a.v[i] : b.v[i])
GC_SIMD4_LANEWISE(max, a.v[i] > b.v[i] ? a.v[i] : b.v[i])
#undef GC_SIMD4_LANEWISE
inline Vec4 xyz(Vec4 a) { return {{a.v[0], a.v[1], a.v[2], 0.0f}}; }
inline void truncate(Vec4 a, std::int32_t* out)
{
    for (int i = 0; i < 4; ++i) out[i] = static_cast<std::int32_t>(a.v[i]);
}
inline void transpose3(Vec4 a, Vec4 b, Vec4 c, Vec4& x, Vec4& y, Vec4& z)
{
    x = {{a.v[0], b.v[0], c.v[0], 0.0f}};
    y = {{a.v[1], b.v[1], c.v[1], 0.0f}};
    z = {{a.v[2], b.v[2], c.v[2], 0.0f}};
}

#endif

}  // namespace gc::simd
