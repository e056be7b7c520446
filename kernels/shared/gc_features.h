/*
 * gc_features.h — the scene features a program is compiled for.
 *
 * The host builds each OpenCL program for the scene it renders (host/render/kernel_features.h):
 * -D GC_USE_TEXTURES=0 when no material samples a texture, and so on for the features below,
 * and GC_USE_MATERIALS as a bitmask of the GC_MAT_* types present. Code guarded by a feature
 * that is off is never reached by that scene's data, so removing it changes no bit of the
 * image (tests/validation/determinism_test.cpp compares against the full program); what it
 * changes is the size of the program: PoCL compiles less (a shorter cold build,
 * docs/decisions/cold-start.md) and the path loop runs in fewer registers (Cycles
 * specialises its kernels by scene features for the same two reasons).
 *
 * Without the defines (the host's C++ use of these headers, the Vulkan reference, a program
 * built by hand) every feature is on. Shared dialect (gc_platform.h).
 */
#ifndef GC_FEATURES_H
#define GC_FEATURES_H

#ifndef GC_USE_TEXTURES
#define GC_USE_TEXTURES 1 /* any material samples a texture (gc_texture.h) */
#endif
#ifndef GC_USE_NORMAL_MAPS
#define GC_USE_NORMAL_MAPS 1 /* any material has a normal texture */
#endif
#ifndef GC_USE_ALPHA_MASK
#define GC_USE_ALPHA_MASK 1 /* any triangle is alpha tested in traversal (GC_TRI_ALPHA_TESTED) */
#endif
#ifndef GC_USE_ALPHA_BLEND
#define GC_USE_ALPHA_BLEND 1 /* any material is glTF alphaMode BLEND */
#endif
#ifndef GC_USE_POINT_LIGHTS
#define GC_USE_POINT_LIGHTS 1
#endif
#ifndef GC_USE_ENV_MAP
#define GC_USE_ENV_MAP 1 /* an environment map (a constant environment needs no code) */
#endif
#ifndef GC_USE_CLEARCOAT
#define GC_USE_CLEARCOAT 1 /* any PBR material has GC_MATF_CLEARCOAT (KHR_materials_clearcoat) */
#endif
#ifndef GC_USE_SPECULAR
#define GC_USE_SPECULAR 1 /* any PBR material has GC_MATF_SPECULAR (KHR_materials_specular) */
#endif
#ifndef GC_USE_SHEEN
#define GC_USE_SHEEN 1 /* any PBR material has GC_MATF_SHEEN (KHR_materials_sheen) */
#endif
#ifndef GC_USE_ROUGH_TRANSMISSION
#define GC_USE_ROUGH_TRANSMISSION 1 /* any PBR material has GC_MATF_ROUGH_TRANSMISSION */
#endif
#ifndef GC_USE_VOLUME
#define GC_USE_VOLUME 1 /* any PBR material has GC_MATF_VOLUME (KHR_materials_volume) */
#endif
#ifndef GC_USE_MATERIALS
#define GC_USE_MATERIALS 0xffffffffu /* bit t: some material has GcMaterial.type t */
#endif

/* Whether material type `type` (a GC_MAT_* constant) may occur. */
#define gc_uses_material(type) ((GC_USE_MATERIALS & (1u << (type))) != 0u)

#endif /* GC_FEATURES_H */
