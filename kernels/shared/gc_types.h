/*
 * gc_types.h — every struct that crosses the host/device boundary, declared once.
 *
 * Compiled as OpenCL C, C++ (namespace gc::dev, with static_asserts at the end) and GLSL
 * (std430). Rules (see gc_platform.h): sizes are multiples of 16, float4/uint4 fields sit at
 * 16-byte offsets, everything else is a 4-byte scalar. kernels/test/layout_probe.cl re-measures
 * every field listed in gc_layout_list.h on each device; tests compare with the host.
 *
 * Integer payloads stored in the .w of a float4 are bit patterns (gc_as_uint), read through
 * the named accessors in gc_accessors.h — never by casting the float.
 */
#ifndef GC_TYPES_H
#define GC_TYPES_H

#include "gc_platform.h"
#include "gc_features.h"

GC_NAMESPACE_BEGIN

/* Ray: origin and direction with the valid parameter interval packed into .w, so a ray is
 * two 16-byte loads. */
GC_STRUCT(GcRay) {
    float4 org_tmin; /* xyz: origin;    w: t_min */
    float4 dir_tmax; /* xyz: direction; w: t_max (need not be normalized) */
} GC_STRUCT_END(GcRay)

/* Closest-hit record. prim is the scene triangle index (not the BVH slot), GC_INVALID on a
 * miss; (u, v) are the barycentrics of v1 and v2. */
GC_STRUCT(GcHit) {
    float t;
    float u;
    float v;
    uint prim;
} GC_STRUCT_END(GcHit)

/* BVH2 node, 32 bytes. Inner node: children are nodes[first] and nodes[first + 1].
 * Leaf: triangles tris[first .. first + count). count == 0 marks an inner node. */
GC_STRUCT(GcBvhNode) {
    float4 lo; /* xyz: bounds min; w: bits of `first` */
    float4 hi; /* xyz: bounds max; w: bits of `count` */
} GC_STRUCT_END(GcBvhNode)

/* BVH4 node, 128 bytes, the layout traversal reads on CPUs (GC_BVH_WIDE, see
 * gc_traverse4.h): the bounds of four children in SoA form, so one ray tests all four boxes
 * with 4-wide SIMD instructions inside one work-item (PoCL cannot vectorise the divergent
 * traversal loop across work-items). Slot k's box is (lo_x.k, lo_y.k, lo_z.k) ..
 * (hi_x.k, hi_y.k, hi_z.k); child.k is a child reference:
 *   GC_INVALID                       empty slot (its bounds are empty: +inf .. -inf);
 *   bit 31 clear                     index of an inner GcBvh4Node;
 *   bit 31 set                       leaf: GcTriangle4 blocks [first, first + count), with
 *                                    first = bits 0..26 and count - 1 = bits 27..30.
 * Node 0 is the root; slots are filled from the first. */
GC_STRUCT(GcBvh4Node) {
    float4 lo_x;
    float4 hi_x;
    float4 lo_y;
    float4 hi_y;
    float4 lo_z;
    float4 hi_z;
    uint4 child;
    uint4 pad; /* root: x = bits of the scene's extent (largest |coordinate| of its bounds,
                * for the traversal's margin, gc_ray_with_extent_margin); otherwise 0 */
} GC_STRUCT_END(GcBvh4Node)

#define GC_BVH4_LEAF 0x80000000u
#define GC_BVH4_LEAF_COUNT_SHIFT 27u
#define GC_BVH4_LEAF_FIRST_MASK 0x07ffffffu
#define GC_BVH4_LEAF_MAX_BLOCKS 16u

/* BVH8 node, 256 bytes, for CPUs with 8-wide SIMD (AVX2, AVX-512): the BVH4 node with eight
 * slots, each quantity split into lanes 0-3 (…0) and 4-7 (…1) so that the struct keeps to
 * float4/uint4 fields (gc_platform.h); the OpenCL traversal reads each pair as one float8
 * (gc_traverse8.h), at float offsets lo_x 0, hi_x 8, lo_y 16, hi_y 24, lo_z 32, hi_z 40:
 * keep the bounds in this order. Child references and leaves as in GcBvh4Node. */
GC_STRUCT(GcBvh8Node) {
    float4 lo_x0;
    float4 lo_x1;
    float4 hi_x0;
    float4 hi_x1;
    float4 lo_y0;
    float4 lo_y1;
    float4 hi_y0;
    float4 hi_y1;
    float4 lo_z0;
    float4 lo_z1;
    float4 hi_z0;
    float4 hi_z1;
    uint4 child0;
    uint4 child1;
    uint4 pad0; /* root: x = bits of the scene's extent, as GcBvh4Node.pad; otherwise 0 */
    uint4 pad1; /* 0; the node is four 64-byte cache lines */
} GC_STRUCT_END(GcBvh8Node)

/* Four triangles of a BVH4 leaf in SoA form, tested together by one ray. Lane k is the
 * triangle (v0x.k, v0y.k, v0z.k), (v1...), (v2...); prim.k is its scene triangle index and
 * flags.k its GC_TRI_* flags. Unused lanes have all vertices at the origin (zero area, never
 * hit) and prim GC_INVALID. */
GC_STRUCT(GcTriangle4) {
    float4 v0x;
    float4 v0y;
    float4 v0z;
    float4 v1x;
    float4 v1y;
    float4 v1z;
    float4 v2x;
    float4 v2y;
    float4 v2z;
    uint4 prim;
    uint4 flags;
} GC_STRUCT_END(GcTriangle4)

/* Triangle in BVH leaf order, as the traversal kernels read it. */
GC_STRUCT(GcTriangle) {
    float4 v0; /* xyz: vertex 0; w: bits of the scene triangle index */
    float4 v1; /* xyz: vertex 1; w: bits of GC_TRI_* flags */
    float4 v2; /* xyz: vertex 2; w: 0 */
} GC_STRUCT_END(GcTriangle)

/* GcTriangle flags (v1.w). GC_TRI_ALPHA_TESTED: the triangle's material is glTF alphaMode
 * MASK with a texture or a cut-away factor, so traversal asks GC_ALPHA_TEST (gc_traverse.h)
 * whether a candidate hit is solid; all other triangles skip the hook. */
#define GC_TRI_ALPHA_TESTED 1u

/* Shading attributes, indexed by scene triangle index. Normals are always present: loaders
 * store the face normal at all three corners when the file has none. */
GC_STRUCT(GcTriangleAttribs) {
    float4 n0;   /* xyz: shading normal at v0; w: bits of v0's authored tangent, packed as
                  * gc_tangent.h says, when flags has GC_TRIF_HAS_TANGENTS (else 0) */
    float4 n1;   /* the same for v1 */
    float4 n2;   /* the same for v2 */
    float4 ng;   /* xyz: unit geometric normal (right-handed winding v0 v1 v2); +z if degenerate;
                  * w: the largest |coordinate| of the three vertices (gc_spawn_scale) */
    float4 uv01; /* xy: uv at v0; zw: uv at v1 */
    float uv2_u;
    float uv2_v;
    uint material;
    uint flags; /* GC_TRIF_* */
    float4 tangent; /* xyz: unit dP/du of the triangle (normal maps); w: bitangent sign, so that
                     * B = w * cross(n, T) points up the image (-dP/dv); zero without usable uvs.
                     * Generated by the host; used where the file gave no tangents (see n0.w) */
} GC_STRUCT_END(GcTriangleAttribs)

#define GC_TRIF_HAS_UV 1u
#define GC_TRIF_HAS_VERTEX_NORMALS 2u
#define GC_TRIF_HAS_TANGENTS 4u /* n0.w .. n2.w hold the file's per-vertex tangents */

/* Material types (GcMaterial.type). Emission is independent of the type. */
#define GC_MAT_LAMBERT 0u    /* albedo / pi */
#define GC_MAT_PHONG 1u      /* albedo / pi + specular (n+2)/(2 pi) cos^n(alpha) */
#define GC_MAT_MIRROR 2u     /* albedo / pi + perfect mirror weighted by specular (MTL illum 3/5) */
#define GC_MAT_DIELECTRIC 3u /* smooth dielectric, ior in emission.w */
#define GC_MAT_PBR 4u        /* glTF metallic-roughness (GGX) */

#define GC_MATF_TWO_SIDED 1u   /* emission on both faces (glTF doubleSided) */
#define GC_MATF_ALPHA_MASK 2u
#define GC_MATF_ALPHA_BLEND 4u
/* GC_MAT_PBR layers from the KHR_materials_* extensions (gc_bsdf.h); a material without the
 * flag never reads the layer's fields, so its result is that of the plain glTF model. */
#define GC_MATF_CLEARCOAT 8u  /* KHR_materials_clearcoat: coat, coat_texture, coat_roughness_texture */
#define GC_MATF_SPECULAR 16u  /* KHR_materials_specular: specular.rgb colour, coat.w factor */
#define GC_MATF_SHEEN 32u     /* KHR_materials_sheen: sheen, sheen_*_texture */
#define GC_MATF_ROUGH_TRANSMISSION 64u /* KHR_materials_transmission with roughness > 0 or a volume: GGX refraction */
#define GC_MATF_VOLUME 128u   /* KHR_materials_volume: absorption_* inside the closed mesh (gc_path_vertex.h) */
/* Set by gc_bsdf.h on its own copy of a rough-transmission material seen from inside; never
 * stored in a scene. */
#define GC_MATF_SEEN_FROM_INSIDE 0x80000000u
/* Set by gc_with_coat_normal on a hit's copy whose coat has its own normal (coat_normal); never
 * stored in a scene. */
#define GC_MATF_COAT_NORMAL 0x40000000u

GC_STRUCT(GcMaterial) {
    float4 albedo;   /* rgb: diffuse reflectance / base color (linear); a: opacity */
    float4 specular; /* rgb: specular or mirror reflectance, or (PBR) KHR_materials_specular colour; a: Phong exponent */
    float4 emission; /* rgb: emitted radiance; a: index of refraction */
    float4 pbr;      /* x: metallic; y: roughness; z: alpha cutoff; w: transmission */
    uint type;       /* GC_MAT_* */
    uint albedo_texture;          /* GcTexture index or GC_INVALID */
    uint metallic_roughness_texture;
    uint normal_texture;
    uint emission_texture;
    uint flags; /* GC_MATF_* */
    float normal_scale; /* glTF normalTexture.scale: multiplies the normal map's tangent-space xy */
    uint coat_texture;  /* clearcoatTexture (R: factor) */
    float4 coat;        /* x: clearcoat factor; y: clearcoat roughness; z: 0; w: KHR_materials_specular factor */
    float4 sheen;       /* KHR_materials_sheen: rgb colour (linear); w: roughness */
    uint coat_roughness_texture; /* clearcoatRoughnessTexture (G: roughness) */
    uint specular_texture;       /* specularTexture (A: factor) */
    uint specular_color_texture; /* specularColorTexture (sRGB rgb: colour) */
    uint sheen_color_texture;    /* sheenColorTexture (sRGB rgb: colour) */
    uint sheen_roughness_texture; /* sheenRoughnessTexture (A: roughness) */
    float absorption_r; /* KHR_materials_volume: sigma_a = -ln(attenuationColor) / attenuationDistance, */
    float absorption_g; /* per unit length and channel (0 without a volume) */
    float absorption_b;
    uint transmission_texture; /* KHR_materials_transmission transmissionTexture (R: factor) */
    uint coat_normal_texture;  /* clearcoatNormalTexture: the coat's own tangent-space normal map */
    float coat_normal_scale;   /* its scale (multiplies the map's xy, as normal_scale) */
    uint pad0;
    float4 coat_normal; /* on a hit's copy with GC_MATF_COAT_NORMAL (gc_with_coat_normal): xyz the
                         * coat's unit normal in the shading frame (z: the shading normal); else 0 */
} GC_STRUCT_END(GcMaterial)

#define GC_TEXF_SRGB 1u          /* texels are sRGB-encoded colour */
#define GC_TEXF_CLAMP_S 2u       /* clamp-to-edge in u, else repeat */
#define GC_TEXF_CLAMP_T 4u
#define GC_TEXF_MIRROR_S 8u
#define GC_TEXF_MIRROR_T 16u
#define GC_TEXF_NEAREST 32u
#define GC_TEXF_TRANSFORM 64u    /* uv_u/uv_v hold a uv transform (glTF KHR_texture_transform) */
#define GC_TEXF_FLOAT 128u       /* texels are linear RGBA float32, four words each (an optimised texture) */

/* A texture view is width * height RGBA8 texels (one uint each, R in the low byte) starting at
 * `offset` in the shared texel buffer, read through an optional affine uv transform: with
 * GC_TEXF_TRANSFORM set, the lookup reads (u', v') = (uv_u.x u + uv_u.y v + uv_u.z,
 * uv_v.x u + uv_v.y v + uv_v.z) (the w components are 0). Several views may share texels
 * (one per distinct transform a material slot asks for, host/render/scene_convert.cpp). */
GC_STRUCT(GcTexture) {
    uint offset;
    uint width;
    uint height;
    uint flags;  /* GC_TEXF_* */
    float4 uv_u; /* u' coefficients of (u, v, 1); w: 0 */
    float4 uv_v; /* v' coefficients of (u, v, 1); w: 0 */
} GC_STRUCT_END(GcTexture)

/* One emissive triangle, for next-event estimation, with its vertices so that sampling a
 * point needs no other lookup. cdf is the inclusive prefix sum of the power-proportional
 * selection probabilities (the last emitter's cdf is exactly 1). */
GC_STRUCT(GcEmitter) {
    float4 v0;     /* xyz: vertex 0 */
    float4 v1;
    float4 v2;
    uint triangle; /* scene triangle index */
    float area;
    float pmf;     /* probability of choosing this emitter */
    float cdf;
} GC_STRUCT_END(GcEmitter)

GC_STRUCT(GcPointLight) {
    float4 position;  /* xyz; w: 0 */
    float4 intensity; /* rgb radiant intensity (W/sr per channel); w: 0 */
} GC_STRUCT_END(GcPointLight)

/* Pinhole camera. A pixel's ray direction is forward + x * right + y * up for x, y in
 * [-1, 1]; right and up are pre-scaled by tan(fov/2) (times the aspect ratio for right). */
GC_STRUCT(GcCamera) {
    float4 origin;
    float4 forward;
    float4 right;
    float4 up;
} GC_STRUCT_END(GcCamera)

#define GC_INTEGRATOR_AOV 0u
#define GC_INTEGRATOR_PATH 1u
#define GC_INTEGRATOR_WHITTED 2u

#define GC_AOV_PREVIEW 0u /* simple shaded preview: albedo * headlight cosine */
#define GC_AOV_ALBEDO 1u
#define GC_AOV_NORMAL 2u  /* shading normal, world space, mapped as is (may be negative) */
#define GC_AOV_DEPTH 3u   /* distance along the ray */
#define GC_AOV_PRIMID 4u  /* scene triangle index as a float, -1 for misses */
/* The denoiser's guides: albedo and shading normal at the first vertex that is not a
 * smooth dielectric or a pure mirror (gc_aov_trace.h), jittered like the beauty. */
#define GC_AOV_GUIDE_ALBEDO 5u
#define GC_AOV_GUIDE_NORMAL 6u

/* GcRenderParams.flags. GC_RENDER_PIXEL_LIST: the path integrator's batch slot i renders the
 * pixel pixel_list[pixel_offset + i] rather than pixel_offset + i (adaptive sampling renders
 * only the pixels still too noisy; gc_batch_pixel). GC_RENDER_SOBOL: the random numbers are
 * low-discrepancy (gc_rng.h's gc_sample4). */
#define GC_RENDER_PIXEL_LIST 1u
#define GC_RENDER_SOBOL 2u

/* The one parameter block every kernel takes. Set in one place on the host. */
GC_STRUCT(GcRenderParams) {
    GcCamera camera;
    float4 env_radiance; /* rgb: constant environment radiance, or the map's scale; w: 0 */
    uint width;
    uint height;
    uint sample_index; /* which sample of each pixel this pass renders */
    uint seed;
    uint max_depth;    /* path segments: 1 = emitters only, 2 = direct light */
    uint integrator;   /* GC_INTEGRATOR_* */
    uint aov;          /* GC_AOV_* when integrator == GC_INTEGRATOR_AOV */
    uint num_triangles;
    uint num_emitters;
    uint num_point_lights;
    uint num_textures;
    uint flags;        /* GC_RENDER_* */
    uint pixel_offset; /* first pixel of this pass's batch (first entry of the pixel list) */
    uint pixel_count;  /* pixels in this pass's batch */
    uint rr_depth;     /* Russian roulette starts at this depth */
    float emitter_power; /* sum over emitters of area * luminance(emission): light pdf norm */
    uint env_width;      /* lat-long environment map size; 0 = constant env_radiance */
    uint env_height;
    uint samples_in_pass; /* path integrator: sample indices sample_index .. + samples_in_pass - 1
                           * in this pass; its paths are pixel_count * samples_in_pass, slot =
                           * pixel slot * samples_in_pass + s (a pixel's samples side by side) */
    uint pixels_per_item; /* CPU path megakernel: neighbouring pixels one work-item renders
                           * (gc_packet_lanes.h); 1 for every other kernel */
} GC_STRUCT_END(GcRenderParams)

/* ---- Wavefront path state (path integrator). One slot per path in flight; a slot owns
 * its pixel for the whole pass, so stages never race on it. */

#define GC_PATH_SPECULAR 1u /* the last bounce was a delta lobe: no MIS on the emitter it hits */
#define GC_PATH_IN_VOLUME 2u /* the last segment runs inside a GC_MATF_VOLUME mesh (refracted in through it) */

GC_STRUCT(GcPathState) {
    float4 throughput; /* rgb: path throughput; w: solid-angle pdf of the last BSDF sample */
    float4 radiance;   /* rgb: radiance gathered so far; w: product of eta^2 over the
                        * refractions so far (Russian roulette; 1 at the camera) */
    uint pixel;
    uint depth;        /* path segments traced so far */
    uint flags;        /* GC_PATH_* */
    uint sample;       /* the pixel sample this path renders (keys its random numbers) */
} GC_STRUCT_END(GcPathState)

/* A next-event-estimation ray: if the segment is unoccluded, contribution is added to the
 * radiance of path slot `slot`. */
GC_STRUCT(GcShadowRay) {
    GcRay ray;
    float4 contribution; /* rgb; w: 0 */
    uint slot;
    uint pad0;
    uint pad1;
    uint pad2;
} GC_STRUCT_END(GcShadowRay)

/* Queue counters, one uint each in a small buffer: two ping-pong ray queues and the
 * shadow queue. Pushed with one atomic_add per work-group (gc_queue.h); read only by the kernels. */
#define GC_COUNTER_RAYS_A 0u
#define GC_COUNTER_RAYS_B 1u
#define GC_COUNTER_SHADOW 2u
#define GC_COUNTER_COUNT 4u

/* The BVH layout the traversal kernels read: BVH2 (GcBvhNode + GcTriangle) unless the host
 * builds the program with -D GC_BVH_WIDE, then BVH4 (GcBvh4Node + GcTriangle4), or with
 * -D GC_BVH_WIDE -D GC_BVH_WIDE8, then BVH8 (GcBvh8Node + GcTriangle4). Kernels declare
 * their BVH buffers with these names, so one source serves every layout. */
#if defined(GC_BVH_WIDE8)
#define GcTraversalNode GcBvh8Node
#define GcTraversalTriangle GcTriangle4
#elif defined(GC_BVH_WIDE)
#define GcTraversalNode GcBvh4Node
#define GcTraversalTriangle GcTriangle4
#else
#define GcTraversalNode GcBvhNode
#define GcTraversalTriangle GcTriangle
#endif

GC_NAMESPACE_END

#if defined(GC_HOST)
#include <cstddef>
#include <type_traits>
/* The host half of the layout contract. The device half is kernels/test/layout_probe.cl. */
namespace gc::dev::layout_check {
#define GC_CHECK_POD(T)                                                                         \
    static_assert(std::is_trivially_copyable_v<T> && std::is_standard_layout_v<T>, #T " must be POD"); \
    static_assert(sizeof(T) % 16 == 0, #T " size must be a multiple of 16")
GC_CHECK_POD(GcRay);
GC_CHECK_POD(GcHit);
GC_CHECK_POD(GcBvhNode);
GC_CHECK_POD(GcTriangle);
GC_CHECK_POD(GcBvh4Node);
GC_CHECK_POD(GcBvh8Node);
GC_CHECK_POD(GcTriangle4);
GC_CHECK_POD(GcTriangleAttribs);
GC_CHECK_POD(GcMaterial);
GC_CHECK_POD(GcTexture);
GC_CHECK_POD(GcEmitter);
GC_CHECK_POD(GcPointLight);
GC_CHECK_POD(GcCamera);
GC_CHECK_POD(GcRenderParams);
GC_CHECK_POD(GcPathState);
GC_CHECK_POD(GcShadowRay);
#undef GC_CHECK_POD
static_assert(sizeof(GcRay) == 32 && offsetof(GcRay, dir_tmax) == 16);
static_assert(sizeof(GcHit) == 16 && offsetof(GcHit, prim) == 12);
static_assert(sizeof(GcBvhNode) == 32 && offsetof(GcBvhNode, hi) == 16);
static_assert(sizeof(GcTriangle) == 48 && offsetof(GcTriangle, v2) == 32);
static_assert(sizeof(GcBvh4Node) == 128 && offsetof(GcBvh4Node, child) == 96);
static_assert(sizeof(GcBvh8Node) == 256 && offsetof(GcBvh8Node, child0) == 192);
static_assert(sizeof(GcTriangle4) == 176 && offsetof(GcTriangle4, prim) == 144);
static_assert(sizeof(GcTriangleAttribs) == 112 && offsetof(GcTriangleAttribs, ng) == 48 &&
              offsetof(GcTriangleAttribs, uv01) == 64 && offsetof(GcTriangleAttribs, uv2_u) == 80 &&
              offsetof(GcTriangleAttribs, flags) == 92 && offsetof(GcTriangleAttribs, tangent) == 96);
static_assert(sizeof(GcMaterial) == 192 && offsetof(GcMaterial, type) == 64 &&
              offsetof(GcMaterial, emission_texture) == 80 && offsetof(GcMaterial, coat) == 96 &&
              offsetof(GcMaterial, sheen) == 112 && offsetof(GcMaterial, coat_roughness_texture) == 128 &&
              offsetof(GcMaterial, sheen_roughness_texture) == 144 && offsetof(GcMaterial, transmission_texture) == 160 &&
              offsetof(GcMaterial, coat_normal_scale) == 168 && offsetof(GcMaterial, coat_normal) == 176);
static_assert(sizeof(GcTexture) == 48 && offsetof(GcTexture, uv_u) == 16 && offsetof(GcTexture, uv_v) == 32);
static_assert(sizeof(GcEmitter) == 64 && offsetof(GcEmitter, triangle) == 48 && offsetof(GcEmitter, cdf) == 60);
static_assert(sizeof(GcPointLight) == 32 && sizeof(GcCamera) == 64);
static_assert(sizeof(GcRenderParams) == 160 && offsetof(GcRenderParams, env_width) == 144 && offsetof(GcRenderParams, env_radiance) == 64 &&
              offsetof(GcRenderParams, width) == 80 && offsetof(GcRenderParams, pixel_offset) == 128 &&
              offsetof(GcRenderParams, emitter_power) == 140);
static_assert(sizeof(GcPathState) == 48 && offsetof(GcPathState, pixel) == 32);
static_assert(sizeof(GcShadowRay) == 64 && offsetof(GcShadowRay, contribution) == 32 &&
              offsetof(GcShadowRay, slot) == 48);
}  // namespace gc::dev::layout_check
#endif

#endif /* GC_TYPES_H */
