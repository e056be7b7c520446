/*
 * gc_platform.h — the few macros that let one header be compiled as OpenCL C 1.2, C++20
 * (host) and GLSL 4.50 (Vulkan compute). Everything in kernels/shared/ includes this first.
 *
 * The shared dialect is the intersection of the three languages:
 *   - vector types are spelled the OpenCL way (float2/float3/float4, uint2/uint4) and built
 *     with make_float3(...) etc., never with casts or constructors directly;
 *   - scalar math uses OpenCL names (sqrt, fabs, fmin, fmax, floor, ...); GLSL gets #defines,
 *     C++ gets using-declarations and a few overloads;
 *   - functions return by value (GLSL has no pointers) and are declared GC_FUNC;
 *   - conversions are gc_float(x) / gc_int(x) / gc_uint(x): C casts are not GLSL, and GLSL
 *     constructors are not C; no % on negative integers (undefined in GLSL);
 *   - structs are declared with GC_STRUCT(Name) { ... } GC_STRUCT_END(Name), are a multiple
 *     of 16 bytes, and hold float4/uint4 or 4-byte scalars only (no float3: OpenCL gives it
 *     16 bytes, std430 packs a following scalar into its tail).
 */
#ifndef GC_PLATFORM_H
#define GC_PLATFORM_H

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
/* ---------------------------------------------------------------- OpenCL C */
#define GC_OPENCL 1
/* Cross-device rule: no fused multiply-add unless the source says fma(). Contraction is on
 * by default in OpenCL C, and a device that fuses rounds differently from one that does not. */
#pragma OPENCL FP_CONTRACT OFF
#define GC_FUNC static inline
/* A kernel's per-work-item body (megakernel.cl, whitted.cl), out of line on CPUs: PoCL inlines
 * a kernel's body into the kernel and into each of its two work-group launchers, so a large
 * body went through the optimiser and the code generator three times on every cold start
 * (megakernel.cl has the figures). The CPU layouts (GC_BVH_WIDE, a build option) mark a CPU;
 * a GPU keeps the body inline, as a call there costs registers. */
#if defined(GC_BVH_WIDE)
#define GC_ITEM_BODY static __attribute__((noinline)) void
#else
#define GC_ITEM_BODY static void
#endif
#define GC_GLOBAL __global
#define GC_CONSTANT __constant
/* A constant float table: GC_FLOAT_TABLE_BEGIN(name, n) v0, v1, ... GC_FLOAT_TABLE_END */
#define GC_FLOAT_TABLE_BEGIN(name, n) __constant float name[n] = {
#define GC_FLOAT_TABLE_END };
#define GC_STRUCT(name) typedef struct name
#define GC_STRUCT_END(name) name;
#define make_float2(x, y) ((float2)((x), (y)))
#define make_float3(x, y, z) ((float3)((x), (y), (z)))
#define make_float4(x, y, z, w) ((float4)((x), (y), (z), (w)))
#define make_uint4(x, y, z, w) ((uint4)((x), (y), (z), (w)))
#define gc_as_uint(f) as_uint(f)
#define gc_as_float(u) as_float(u)
#define GC_XYZ(v) ((v).xyz)
#define gc_float(x) ((float)(x))
#define gc_int(x) ((int)(x))
#define gc_uint(x) ((uint)(x))

#elif defined(__cplusplus)
/* ---------------------------------------------------------------- C++ host */
#define GC_HOST 1
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace gc::dev {
using uint = std::uint32_t;
using float2 = glm::vec2;
using float3 = glm::vec3;
using float4 = glm::vec4;
using uint2 = glm::uvec2;
using uint4 = glm::uvec4;

using std::cos;
using std::exp;
using std::fabs;
using std::floor;
using std::fmax;
using std::fmin;
using std::log;
using std::pow;
using std::sin;
using std::sqrt;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::length;
using glm::mix;
using glm::normalize;

inline float2 make_float2(float x, float y) { return {x, y}; }
inline float3 make_float3(float x, float y, float z) { return {x, y, z}; }
inline float4 make_float4(float x, float y, float z, float w) { return {x, y, z, w}; }
inline uint4 make_uint4(uint x, uint y, uint z, uint w) { return {x, y, z, w}; }
inline uint gc_as_uint(float f) { return std::bit_cast<uint>(f); }
inline float gc_as_float(uint u) { return std::bit_cast<float>(u); }
inline float3 fmin(float3 a, float3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
inline float3 fmax(float3 a, float3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }
inline float3 fabs(float3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline float4 fmin(float4 a, float4 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z), std::fmin(a.w, b.w)}; }
inline float4 fmax(float4 a, float4 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z), std::fmax(a.w, b.w)}; }
inline float4 fabs(float4 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z), std::fabs(a.w)}; }
}  // namespace gc::dev

#define GC_FUNC inline
#define GC_GLOBAL
#define GC_CONSTANT
#define GC_FLOAT_TABLE_BEGIN(name, n) namespace gc::dev { inline constexpr float name[n] = {
#define GC_FLOAT_TABLE_END }; }
/* alignas(16) makes the host struct's size and alignment equal OpenCL's and std430's. */
#define GC_STRUCT(name) struct alignas(16) name
#define GC_STRUCT_END(name) ;
#define GC_XYZ(v) (::gc::dev::float3((v).x, (v).y, (v).z))
#define gc_float(x) static_cast<float>(x)
#define gc_int(x) static_cast<int>(x)
#define gc_uint(x) static_cast<::gc::dev::uint>(x)
#define GC_NAMESPACE_BEGIN namespace gc::dev {
#define GC_NAMESPACE_END }

#else
/* ---------------------------------------------------------------- GLSL (Vulkan) */
#define GC_GLSL 1
#define GC_FUNC
#define GC_GLOBAL
#define GC_CONSTANT const
#define GC_FLOAT_TABLE_BEGIN(name, n) const float name[n] = float[n](
#define GC_FLOAT_TABLE_END );
#define GC_STRUCT(name) struct name
#define GC_STRUCT_END(name) ;
#define float2 vec2
#define float3 vec3
#define float4 vec4
#define uint2 uvec2
#define uint4 uvec4
#define make_float2 vec2
#define make_float3 vec3
#define make_float4 vec4
#define make_uint4 uvec4
#define fabs abs
#define fmin min
#define fmax max
#define gc_as_uint floatBitsToUint
#define gc_as_float uintBitsToFloat
#define GC_XYZ(v) ((v).xyz)
#define gc_float(x) float(x)
#define gc_int(x) int(x)
#define gc_uint(x) uint(x)
#endif

#ifndef GC_NAMESPACE_BEGIN
#define GC_NAMESPACE_BEGIN
#define GC_NAMESPACE_END
#endif

#define GC_PI 3.14159265358979323846f
#define GC_INV_PI 0.31830988618379067154f
#define GC_INV_2PI 0.15915494309189533577f
#define GC_FLOAT_MAX 3.402823466e+38f
/* Marks "no primitive" in hit records and "no texture" in materials. */
#define GC_INVALID 0xffffffffu

#endif /* GC_PLATFORM_H */
