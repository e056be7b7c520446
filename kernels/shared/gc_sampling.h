/*
 * gc_sampling.h — warps from uniform random numbers in [0,1) to the domains the path tracer
 * samples (disk, hemisphere, sphere, triangle, Phong lobe), their densities, the power
 * heuristic for multiple importance sampling, and luminance.
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2, C++20 (gc::dev) and GLSL 4.50 — functions
 * return by value, no pointers, float literals only. Directions are unit float3; densities
 * are per unit solid angle (per unit area for the disk and triangle).
 */
#ifndef GC_SAMPLING_H
#define GC_SAMPLING_H

#include "gc_platform.h"
#include "gc_frame.h"
#include "gc_pow.h"
#include "gc_trig.h"

GC_NAMESPACE_BEGIN

/* Rec. 709 / sRGB-primaries luminance of linear RGB: used to choose between lobes, so only
 * its proportions matter. */
GC_FUNC float gc_luminance(float3 rgb)
{
    return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

/* Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square": the concentric map
 * sends nested squares of [-1,1]^2 to nested circles, so strata stay compact and the
 * density is uniform (1/pi per unit area). Returns a point in the unit disk. */
GC_FUNC float2 gc_sample_concentric_disk(float u0, float u1)
{
    float a = 2.0f * u0 - 1.0f;
    float b = 2.0f * u1 - 1.0f;
    if (a == 0.0f && b == 0.0f) return make_float2(0.0f, 0.0f);
    /* phi = pi/4 (b/a) in the first case, pi/2 - pi/4 (a/b) in the second, whose cosine and
     * sine are the sine and cosine of pi/4 (a/b): both angles stay within [-pi/4, pi/4]. */
    if (fabs(a) > fabs(b)) {
        const float2 cs = gc_cos_sin_quarter((0.25f * GC_PI) * (b / a));
        return make_float2(a * cs.x, a * cs.y);
    }
    const float2 cs = gc_cos_sin_quarter((0.25f * GC_PI) * (a / b));
    return make_float2(b * cs.y, b * cs.x);
}

/* Malley's method: lift a uniform disk point to the hemisphere; the projection makes the
 * density cos(theta)/pi. The result has z >= 0 (z == 0 only on the disk's rim). z comes from
 * the concentric map's radius max(|a|, |b|), not from x^2 + y^2, so it involves no
 * transcendental: every device agrees on it exactly, in particular on whether z == 0. */
GC_FUNC float3 gc_sample_cosine_hemisphere(float u0, float u1)
{
    float2 d = gc_sample_concentric_disk(u0, u1);
    float r = fmax(fabs(2.0f * u0 - 1.0f), fabs(2.0f * u1 - 1.0f));
    float z = sqrt(fmax(0.0f, (1.0f - r) * (1.0f + r)));
    return make_float3(d.x, d.y, z);
}

/* Density of gc_sample_cosine_hemisphere over solid angle, for a direction with this z. */
GC_FUNC float gc_cosine_hemisphere_pdf(float cos_theta)
{
    return fmax(cos_theta, 0.0f) * GC_INV_PI;
}

/* Archimedes: z uniform in [-1,1] and phi uniform give a uniform sphere. */
GC_FUNC float3 gc_sample_uniform_sphere(float u0, float u1)
{
    float z = 1.0f - 2.0f * u0;
    float r = sqrt(fmax(0.0f, 1.0f - z * z));
    const float2 cs = gc_cos_sin_turns(u1);
    return make_float3(r * cs.x, r * cs.y, z);
}

GC_FUNC float gc_uniform_sphere_pdf(void)
{
    return 0.25f * GC_INV_PI;
}

/* Heitz 2019, "A Low-Distortion Map Between Triangle and Square": fold the square along
 * its diagonal and shear, which keeps neighbourhoods compact (unlike the sqrt map) and needs
 * no transcendental. Returns the barycentrics (b0, b1, b2) of v0, v1, v2: each >= 0, sum 1,
 * uniform over the triangle (density 1/area). */
GC_FUNC float3 gc_sample_uniform_triangle(float u0, float u1)
{
    float b0;
    float b1;
    if (u0 < u1) {
        b0 = 0.5f * u0;
        b1 = u1 - b0;
    } else {
        b1 = 0.5f * u1;
        b0 = u0 - b1;
    }
    return make_float3(b0, b1, 1.0f - b0 - b1);
}

/* Phong lobe cos^n(alpha) around +z, normalised over the whole sphere (alpha in [0, pi/2]
 * carries all the mass): pdf = (n+1)/(2 pi) cos^n(alpha). Inverting the cdf of cos(alpha)
 * gives cos(alpha) = xi^(1/(n+1)); 1-u keeps pow's argument positive (GLSL leaves pow(0, y)
 * undefined only for y <= 0, but this also keeps the pole reachable). */
GC_FUNC float gc_phong_lobe_pdf(float cos_alpha, float exponent)
{
    if (cos_alpha <= 0.0f) return 0.0f;
    return (exponent + 1.0f) * GC_INV_2PI * gc_pow(cos_alpha, exponent);
}

/* Direction distributed as gc_phong_lobe_pdf around the unit vector `axis`. It may point
 * below any surface the axis sits on; callers reject such samples. */
GC_FUNC float3 gc_sample_phong_lobe(float3 axis, float exponent, float u0, float u1)
{
    float cos_a = gc_pow(1.0f - u0, 1.0f / (exponent + 1.0f));
    float sin_a = sqrt(fmax(0.0f, 1.0f - cos_a * cos_a));
    const float2 cs = gc_cos_sin_turns(u1);
    float3 d = make_float3(sin_a * cs.x, sin_a * cs.y, cos_a);
    return gc_frame_to_world(gc_frame_from_normal(axis), d);
}

/* Veach 1997, power heuristic with beta = 2, one sample from each strategy: the weight of
 * a sample drawn with density pdf_a when pdf_b could also have produced it. Written as a
 * ratio so huge or infinite densities give 0 or 1 instead of inf/inf. */
GC_FUNC float gc_power_heuristic(float pdf_a, float pdf_b)
{
    if (!(pdf_a > 0.0f)) return 0.0f;
    float r = pdf_b / pdf_a;
    return 1.0f / (1.0f + r * r);
}

/* Mirror direction of w about the local normal +z. */
GC_FUNC float3 gc_reflect_z(float3 w)
{
    return make_float3(-w.x, -w.y, w.z);
}

GC_NAMESPACE_END

#endif /* GC_SAMPLING_H */
