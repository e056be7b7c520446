/*
 * gc_texture.h — bilinear texture lookups from the shared RGBA8 texel buffer.
 *
 * Textures are plain buffers, not OpenCL image objects: PoCL and lavapipe differ in image
 * support, and filtering done here in IEEE float arithmetic is identical on every device.
 * The texel buffer is reached through GC_TEXELS_PARAM / GC_TEXEL(i) (gc_scene_buffers.h;
 * GLSL reads an SSBO, kernels/vk/scene_bindings.glsl).
 */
#ifndef GC_TEXTURE_H
#define GC_TEXTURE_H

#include "gc_scene_buffers.h"
#include "gc_srgb_table.h"
#include "gc_types.h"

GC_NAMESPACE_BEGIN

GC_FUNC float4 gc_unpack_texel(uint packed, bool srgb)
{
    const uint r = packed & 255u;
    const uint g = (packed >> 8u) & 255u;
    const uint b = (packed >> 16u) & 255u;
    const float a = gc_float(packed >> 24u) * (1.0f / 255.0f);
    if (srgb)
        return make_float4(gc_srgb_to_linear_table[r], gc_srgb_to_linear_table[g],
                           gc_srgb_to_linear_table[b], a);
    return make_float4(gc_float(r) * (1.0f / 255.0f), gc_float(g) * (1.0f / 255.0f),
                       gc_float(b) * (1.0f / 255.0f), a);
}

/* Applies a wrap mode to a texture coordinate, in float so that huge coordinates cannot
 * overflow an integer: the result is in [0, 1]. */
GC_FUNC float gc_wrap_unit(float t, bool clamp_edge, bool mirror)
{
    if (clamp_edge) return clamp(t, 0.0f, 1.0f);
    if (mirror) {
        const float m = t - 2.0f * floor(0.5f * t); /* [0, 2) */
        return m < 1.0f ? m : 2.0f - m;
    }
    return t - floor(t);
}

/* Texel index for x in [-1, size]: the neighbour just outside the edge wraps around for
 * repeat and is clamped for clamp and mirror (mirror repeats the edge texel). */
GC_FUNC uint gc_wrap_index(int x, int size, bool repeat)
{
    if (repeat) return gc_uint((x + size) - ((x + size) / size) * size);
    return gc_uint(x < 0 ? 0 : (x >= size ? size - 1 : x));
}

/* The texels a lookup at (u, v) reads: their indices within the view's texture (row-major,
 * texel (x, y) is y * width + x) and the bilinear fractions, or one texel for nearest
 * filtering. The lookup (gc_texture_sample) and the adjoint, which scatters a lookup's
 * gradient back to its texels, both start from it. Register-only. */
GC_STRUCT(GcTexelFootprint) {
    uint4 index;  /* (x0, y0), (x1, y0), (x0, y1), (x1, y1); nearest: index.x only */
    float2 frac;  /* bilinear fx, fy */
    uint nearest;
} GC_STRUCT_END(GcTexelFootprint)

GC_FUNC GcTexelFootprint gc_texture_footprint(GcTexture tex, float u, float v)
{
    /* A view's uv transform (KHR_texture_transform), only where the view has one, so that
     * untransformed lookups keep their bits. Terms in a fixed order; no contraction. */
    if ((tex.flags & GC_TEXF_TRANSFORM) != 0u) {
        const float tu = (tex.uv_u.x * u + tex.uv_u.y * v) + tex.uv_u.z;
        const float tv = (tex.uv_v.x * u + tex.uv_v.y * v) + tex.uv_v.z;
        u = tu;
        v = tv;
    }
    /* Non-finite coordinates (a broken mesh, a huge transform) read a texel instead of indexing out of bounds. */
    if (!(fabs(u) < 1.0e7f)) u = 0.0f;
    if (!(fabs(v) < 1.0e7f)) v = 0.0f;
    const bool clamp_s = (tex.flags & GC_TEXF_CLAMP_S) != 0u;
    const bool clamp_t = (tex.flags & GC_TEXF_CLAMP_T) != 0u;
    const bool mirror_s = (tex.flags & GC_TEXF_MIRROR_S) != 0u;
    const bool mirror_t = (tex.flags & GC_TEXF_MIRROR_T) != 0u;
    const int w = gc_int(tex.width);
    const int h = gc_int(tex.height);
    const float x = gc_wrap_unit(u, clamp_s, mirror_s) * gc_float(w) - 0.5f;
    const float y = gc_wrap_unit(v, clamp_t, mirror_t) * gc_float(h) - 0.5f;
    const bool repeat_s = !clamp_s && !mirror_s;
    const bool repeat_t = !clamp_t && !mirror_t;

    GcTexelFootprint fp;
    if ((tex.flags & GC_TEXF_NEAREST) != 0u) {
        const uint xi = gc_wrap_index(gc_int(floor(x + 0.5f)), w, repeat_s);
        const uint yi = gc_wrap_index(gc_int(floor(y + 0.5f)), h, repeat_t);
        fp.index = make_uint4(yi * tex.width + xi, 0u, 0u, 0u);
        fp.frac = make_float2(0.0f, 0.0f);
        fp.nearest = 1u;
        return fp;
    }
    const float x0 = floor(x);
    const float y0 = floor(y);
    const uint xa = gc_wrap_index(gc_int(x0), w, repeat_s);
    const uint xb = gc_wrap_index(gc_int(x0) + 1, w, repeat_s);
    const uint ya = gc_wrap_index(gc_int(y0), h, repeat_t);
    const uint yb = gc_wrap_index(gc_int(y0) + 1, h, repeat_t);
    fp.index = make_uint4(ya * tex.width + xa, ya * tex.width + xb, yb * tex.width + xa, yb * tex.width + xb);
    fp.frac = make_float2(x - x0, y - y0);
    fp.nearest = 0u;
    return fp;
}

/* Texel `index` of the view's texture, linear RGBA. */
GC_FUNC float4 gc_texel_value(GC_TEXELS_PARAM, GcTexture tex, uint index)
{
    if ((tex.flags & GC_TEXF_FLOAT) != 0u) {
        const uint w = tex.offset + 4u * index;
        return make_float4(gc_as_float(GC_TEXEL(w)), gc_as_float(GC_TEXEL(w + 1u)), gc_as_float(GC_TEXEL(w + 2u)),
                           gc_as_float(GC_TEXEL(w + 3u)));
    }
    return gc_unpack_texel(GC_TEXEL(tex.offset + index), (tex.flags & GC_TEXF_SRGB) != 0u);
}

GC_FUNC float4 gc_texture_sample(GC_TEXELS_PARAM, GcTexture tex, float u, float v)
{
    const GcTexelFootprint fp = gc_texture_footprint(tex, u, v);
    if (fp.nearest != 0u) return gc_texel_value(GC_TEXELS_ARG, tex, fp.index.x);
    const float fx = fp.frac.x;
    const float fy = fp.frac.y;
    const float4 t00 = gc_texel_value(GC_TEXELS_ARG, tex, fp.index.x);
    const float4 t10 = gc_texel_value(GC_TEXELS_ARG, tex, fp.index.y);
    const float4 t01 = gc_texel_value(GC_TEXELS_ARG, tex, fp.index.z);
    const float4 t11 = gc_texel_value(GC_TEXELS_ARG, tex, fp.index.w);
    const float4 top = t00 * (1.0f - fx) + t10 * fx;
    const float4 bottom = t01 * (1.0f - fx) + t11 * fx;
    return top * (1.0f - fy) + bottom * fy;
}

/* A normal map's tangent-space (x, y) as the mesh's frame sees them. The map stores x along
 * the direction in which the *looked-up* u grows and y up its image (against its v); through
 * a transformed view (u', v') = A (u, v) + c, those are the mesh frame's (T, B) mapped by A's
 * inverse: x T' + y B' = ((e x + b y) T + (d x + a y) B) / det A for rows (a b c; d e f).
 * Scaled by sqrt(|det A|), so that a rotation with a uniform scale only turns (x, y) and a
 * mirror flips it. Untransformed views, and degenerate transforms, return (x, y) unchanged. */
GC_FUNC float2 gc_texture_tangent_xy(GcTexture tex, float x, float y)
{
    if ((tex.flags & GC_TEXF_TRANSFORM) == 0u) return make_float2(x, y);
    const float a = tex.uv_u.x;
    const float b = tex.uv_u.y;
    const float d = tex.uv_v.x;
    const float e = tex.uv_v.y;
    const float det = a * e - b * d;
    const float k = sqrt(fabs(det)) / det;
    if (!(fabs(k) < 1.0e30f) || !(fabs(det) > 0.0f)) return make_float2(x, y);
    return make_float2((e * x + b * y) * k, (d * x + a * y) * k);
}

GC_NAMESPACE_END

#endif /* GC_TEXTURE_H */
