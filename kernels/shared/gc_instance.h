/*
 * gc_instance.h — what an instance of a mesh is on the device (GcInstance), the closest-hit
 * record of an instanced scene (GcInstanceHit), and the ray's map into object space.
 * Traversal: gc_traverse_instances.h. Shared dialect (gc_platform.h).
 */
#ifndef GC_INSTANCE_H
#define GC_INSTANCE_H

#include "gc_intersect.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

/* One instance, 64 bytes. */
GC_STRUCT(GcInstance) {
    float4 row0;    /* world-to-object affine map, row by row: xyz the linear part, w the */
    float4 row1;    /* translation; object = (row . (world, 1)) per coordinate */
    float4 row2;
    uint node_base; /* the mesh's root in the layout's node array */
    uint tri_base;  /* the mesh's first triangle (BVH2) or block (BVH4/8) in that layout */
    uint id;        /* the instance's index in the scene, for the tie rule and the hit */
    uint mesh;      /* the mesh it copies */
} GC_STRUCT_END(GcInstance)

/* Closest hit of an instanced scene: hit.prim is the triangle's index in the scene of meshes,
 * instance the instance's id and slot its index in the instance buffer (leaf order), where
 * shading finds its transform. */
GC_STRUCT(GcInstanceHit) {
    GcHit hit;
    uint instance;
    uint slot;
    uint pad1;
    uint pad2;
} GC_STRUCT_END(GcInstanceHit)

GC_FUNC GcInstanceHit gc_no_instance_hit(void)
{
    GcInstanceHit h;
    h.hit = gc_no_hit();
    h.instance = GC_INVALID;
    h.slot = GC_INVALID;
    h.pad1 = 0u;
    h.pad2 = 0u;
    return h;
}

/* A normal from the instance's object space to world space: by the inverse transpose of
 * object-to-world, which is the transpose of the stored world-to-object map; unit length. */
GC_FUNC float3 gc_instance_normal_to_world(GcInstance inst, float3 n)
{
    const float3 w = make_float3((inst.row0.x * n.x + inst.row1.x * n.y) + inst.row2.x * n.z,
                                 (inst.row0.y * n.x + inst.row1.y * n.y) + inst.row2.y * n.z,
                                 (inst.row0.z * n.x + inst.row1.z * n.y) + inst.row2.z * n.z);
    return gc_normalize(w);
}

GC_FUNC float gc_affine_row(float4 row, float x, float y, float z, float w)
{
    /* Fixed order, no contraction (gc_platform.h): every device rounds alike. */
    return ((row.x * x + row.y * y) + row.z * z) + row.w * w;
}

/* The ray in the instance's object space, same parameterisation (t unchanged). */
GC_FUNC GcRay gc_instance_ray(GcInstance inst, GcRay ray)
{
    float4 o = ray.org_tmin;
    float4 d = ray.dir_tmax;
    GcRay r;
    r.org_tmin = make_float4(gc_affine_row(inst.row0, o.x, o.y, o.z, 1.0f), gc_affine_row(inst.row1, o.x, o.y, o.z, 1.0f),
                             gc_affine_row(inst.row2, o.x, o.y, o.z, 1.0f), o.w);
    r.dir_tmax = make_float4(gc_affine_row(inst.row0, d.x, d.y, d.z, 0.0f), gc_affine_row(inst.row1, d.x, d.y, d.z, 0.0f),
                             gc_affine_row(inst.row2, d.x, d.y, d.z, 0.0f), d.w);
    return r;
}

GC_NAMESPACE_END

#if defined(GC_HOST)
static_assert(sizeof(gc::dev::GcInstance) == 64 && offsetof(gc::dev::GcInstance, node_base) == 48);
static_assert(sizeof(gc::dev::GcInstanceHit) == 32 && offsetof(gc::dev::GcInstanceHit, instance) == 16);
#endif

#endif /* GC_INSTANCE_H */
