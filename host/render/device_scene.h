// A scene resident on one OpenCL device: the BVH in the device's layout, shading attributes,
// materials, textures and lights, in the layouts of kernels/shared/gc_types.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <tuple>

#include "gc_types.h"
#include "host/bvh/big_array.h"
#include "host/bvh/bvh.h"
#include "host/cl/buffer.h"
#include "host/render/device_bvh.h"
#include "host/render/device_tuning.h"
#include "host/render/environment.h"
#include "host/render/kernel_features.h"
#include "host/render/scene_buffers.h"
#include "host/render/scene_convert.h"
#include "host/scene/instances.h"
#include "host/scene/scene.h"

namespace gc {

struct DeviceScene {
    // The triangle attributes' host array, which CPU devices read in place (like the wide
    // BVH's arrays in DeviceBvh). Declared before the buffers so that it outlives them.
    std::shared_ptr<const BigArray<dev::GcTriangleAttribs>> host_attribs;
    DeviceBvh bvh;  // BVH2 or BVH4, as bvh_layout_for chose; an instanced scene's meshes' trees
    // An instanced scene's top level (upload_instanced); empty for a flat scene.
    DeviceInstanceLevel instance_level;
    cl::Buffer<dev::GcTriangleAttribs> attribs;
    cl::Buffer<dev::GcMaterial> materials;
    cl::Buffer<dev::GcTexture> textures;
    cl::Buffer<std::uint32_t> texels;
    cl::Buffer<dev::GcEmitter> emitters;
    cl::Buffer<dev::GcPointLight> point_lights;
    cl::Buffer<glm::vec4> env_pixels;
    cl::Buffer<float> env_marginal;
    cl::Buffer<float> env_conditional;

    std::uint32_t triangle_count = 0;
    std::uint32_t emitter_count = 0;
    std::uint32_t point_light_count = 0;
    std::uint32_t texture_count = 0;
    std::uint32_t env_width = 0;  // 0: no environment map
    std::uint32_t env_height = 0;
    std::string env_source;       // the uploaded map's EnvironmentMap::source
    SceneSummary summary;         // what the kernels' parameters say about the scene
    KernelFeatureSet feature_set = KernelFeatureSet::Scene;
    KernelFeatures features;      // what the programs rendering this scene must handle
    // Bumped by every update: a renderer that sees it change restarts its film, since samples
    // of the old scene and the new one do not average into either.
    std::uint64_t revision = 0;

    // Bytes of device memory the scene occupies (reported by --verbose and the benchmark).
    std::uint64_t bytes() const;

    // Whether the scene is traced through the two-level BVH: its programs are built with
    // -D GC_SCENE_INSTANCED (scene_program_options) and take instance_args() before the
    // scene's buffers.
    bool instanced() const { return instance_level.instances.count() > 0; }
    auto instance_args() const  // GC_INSTANCE_PARAMS
    {
        return std::tuple_cat(scene_buffers::arg(instance_level.tlas), scene_buffers::arg(instance_level.instances));
    }

    // Kernel argument groups for cl::Kernel::set_args, each the twin of one parameter macro of
    // kernels/shared, generated from the same list (gc_scene_buffers.h), so they agree in order
    // and number. The tuples refer to this scene's buffers: pass them to set_args, do not keep
    // them.
    auto alpha_args() const { return GC_DEVICE_SCENE_ARGS(ALPHA); }    // GC_ALPHA_PARAMS
    auto lights_args() const { return GC_DEVICE_SCENE_ARGS(LIGHTS); }  // GC_LIGHTS_PARAMS
    auto bvh_args() const { return GC_DEVICE_SCENE_ARGS(TRACE); }      // GC_BVH_PARAMS (extend, shadow)
    auto shade_args() const { return GC_DEVICE_SCENE_ARGS(SHADE); }    // GC_SHADE_PARAMS (shade)
    auto scene_args() const  // GC_SCENE_PARAMS (path_megakernel, aov_render, whitted_render)
    {
        return GC_DEVICE_SCENE_ARGS(SCENE);
    }

    // Replaces the materials, and the emitters they make (an emission edit changes which
    // triangles emit and how strongly), from `scene`: the uploaded scene with its materials
    // edited, so the same triangles and the same number of materials (UsageError otherwise).
    // The geometry, the BVH and the texels stay on the device (the texture views, which the
    // materials' uv transforms choose, are made again); a renderer rebuilds its
    // program only if the edit changed the kernel features.
    void update_materials(const cl::Context& context, const Scene& scene);
    // As update_materials, and the texels too (an optimiser's edit of a texture, which may
    // now be stored as linear floats, Texture::linear).
    void update_textures(const cl::Context& context, const Scene& scene);

    static DeviceScene upload(const cl::Context& context, const Scene& scene, const FlatBvh& bvh,
                              const EnvironmentMap& environment = {}, const DeviceTuning& tuning = {});
    // An instanced scene: each mesh once (its tree from `bvh`, built by build_instance_bvh),
    // the instances' top level, and shading data for the meshes' triangles followed by every
    // instance's emissive triangles in world space (with_world_emitters), which the emitters
    // index. Material and texture updates are refused (UsageError).
    static DeviceScene upload_instanced(const cl::Context& context, const InstancedScene& scene,
                                        const InstanceBvhParts& bvh, const EnvironmentMap& environment = {},
                                        const DeviceTuning& tuning = {});

private:
    // Everything but the BVH, from `scene`; emitters among its triangles from `first_emitter` on.
    void upload_shading(const cl::Context& context, const Scene& scene, std::uint32_t first_emitter,
                        const EnvironmentMap& environment, const DeviceTuning& tuning);
    // UsageError unless `scene` has the uploaded scene's triangles and materials.
    void check_update(const Scene& scene, const char* what) const;
    // The materials, texture views, emitters and summary from `scene`, and a new revision.
    void apply_material_update(const cl::Context& context, const Scene& scene);
};

}  // namespace gc
