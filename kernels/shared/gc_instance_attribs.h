/*
 * gc_instance_attribs.h — a hit triangle's shading attributes taken from its instance's object
 * space to world space, so that the path vertex (gc_shade_surface) shades an instanced hit
 * exactly as it shades a flat one: the world ray, the world t, world normals and tangents.
 *
 * The instance stores only its world-to-object map W (gc_instance.h). Normals go by the
 * transpose of W (the inverse transpose of object-to-world M); tangents, which are directions
 * on the surface, by M itself, here W's adjugate: adj(W) = det(W) M, so the direction is right
 * after normalising once the sign of det(W) is applied. The geometric normal keeps its object
 * side: the glTF loader swaps the winding of a mirrored node's triangles so that the face the
 * file calls front stays front, and an instance of it must agree. For the same reason a
 * mirrored instance flips the bitangent sign (B = w cross(N, T) in glTF): the flat loader does
 * the same (gltf_loader.cpp).
 *
 * The spawn offset's scale (ng.w, the largest |coordinate| of the triangle) becomes a bound on
 * the world vertices' coordinates: each row of M times the object bound plus the translation.
 * It is at least the true value, so rays still start clear of the surface; it is not the flat
 * scene's value, so the two scenes' images agree within noise, not bit for bit.
 * Shared dialect (gc_platform.h).
 */
#ifndef GC_INSTANCE_ATTRIBS_H
#define GC_INSTANCE_ATTRIBS_H

#include "gc_instance.h"
#include "gc_tangent.h"

GC_NAMESPACE_BEGIN

/* Object-to-world's linear part times det(W) (W's adjugate, row by row) and det(W). */
GC_STRUCT(GcInstanceAdjugate) {
    float3 r0;
    float3 r1;
    float3 r2;
    float det;
} GC_STRUCT_END(GcInstanceAdjugate)

GC_FUNC GcInstanceAdjugate gc_instance_adjugate(GcInstance inst)
{
    const float3 a = GC_XYZ(inst.row0);
    const float3 b = GC_XYZ(inst.row1);
    const float3 c = GC_XYZ(inst.row2);
    /* The inverse's columns are cross products of W's rows, over det(W). */
    const float3 c0 = gc_cross(b, c);
    const float3 c1 = gc_cross(c, a);
    const float3 c2 = gc_cross(a, b);
    GcInstanceAdjugate adj;
    adj.r0 = make_float3(c0.x, c1.x, c2.x);
    adj.r1 = make_float3(c0.y, c1.y, c2.y);
    adj.r2 = make_float3(c0.z, c1.z, c2.z);
    adj.det = gc_dot(a, c0);
    return adj;
}

/* An object-space direction on the surface in world space, unit length (zero stays zero). */
GC_FUNC float3 gc_instance_direction_to_world(GcInstanceAdjugate adj, float3 v)
{
    const float3 w = make_float3(gc_dot(adj.r0, v), gc_dot(adj.r1, v), gc_dot(adj.r2, v));
    const float len = gc_length(w);
    const float sign = adj.det < 0.0f ? -1.0f : 1.0f;
    return len > 0.0f ? w * (sign / len) : w;
}

/* A packed authored tangent (gc_tangent.h) in world space, repacked. */
GC_FUNC float gc_instance_tangent_bits(GcInstanceAdjugate adj, float packed)
{
    const float4 t = gc_tangent_decode(gc_as_uint(packed));
    const float3 w = gc_instance_direction_to_world(adj, GC_XYZ(t));
    const float sign = adj.det < 0.0f ? -t.w : t.w;
    return gc_as_float(gc_tangent_encode(w, sign));
}

GC_FUNC GcTriangleAttribs gc_instance_attribs(GcInstance inst, GcTriangleAttribs a)
{
    const GcInstanceAdjugate adj = gc_instance_adjugate(inst);
    GcTriangleAttribs w = a;
    const float3 n0 = gc_instance_normal_to_world(inst, GC_XYZ(a.n0));
    const float3 n1 = gc_instance_normal_to_world(inst, GC_XYZ(a.n1));
    const float3 n2 = gc_instance_normal_to_world(inst, GC_XYZ(a.n2));
    const bool tangents = (a.flags & GC_TRIF_HAS_TANGENTS) != 0u;
    w.n0 = make_float4(n0.x, n0.y, n0.z, tangents ? gc_instance_tangent_bits(adj, a.n0.w) : a.n0.w);
    w.n1 = make_float4(n1.x, n1.y, n1.z, tangents ? gc_instance_tangent_bits(adj, a.n1.w) : a.n1.w);
    w.n2 = make_float4(n2.x, n2.y, n2.z, tangents ? gc_instance_tangent_bits(adj, a.n2.w) : a.n2.w);

    /* |world coordinate i| <= sum_j |M_ij| * extent + |t_i|, with M = adj / det and the
     * translation t = -M W_t (W_t: W's translation column). */
    const float inv_det = 1.0f / fabs(adj.det);
    const float3 wt = make_float3(inst.row0.w, inst.row1.w, inst.row2.w);
    const float3 r0 = adj.r0 * inv_det;
    const float3 r1 = adj.r1 * inv_det;
    const float3 r2 = adj.r2 * inv_det;
    const float extent = a.ng.w;
    const float x = (fabs(r0.x) + fabs(r0.y) + fabs(r0.z)) * extent + fabs(gc_dot(r0, wt));
    const float y = (fabs(r1.x) + fabs(r1.y) + fabs(r1.z)) * extent + fabs(gc_dot(r1, wt));
    const float z = (fabs(r2.x) + fabs(r2.y) + fabs(r2.z)) * extent + fabs(gc_dot(r2, wt));
    const float3 ng = gc_instance_normal_to_world(inst, GC_XYZ(a.ng));
    w.ng = make_float4(ng.x, ng.y, ng.z, fmax(x, fmax(y, z)));

    /* The generated tangent: a direction, and its bitangent sign flips with the handedness. */
    const float3 t = gc_instance_direction_to_world(adj, GC_XYZ(a.tangent));
    w.tangent = make_float4(t.x, t.y, t.z, adj.det < 0.0f ? -a.tangent.w : a.tangent.w);
    return w;
}

GC_NAMESPACE_END

#endif /* GC_INSTANCE_ATTRIBS_H */
