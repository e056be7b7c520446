// The one place host types become the device layouts of kernels/shared/gc_types.h.
// Pure functions of the scene: no device needed, so tests check them on the host.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gc_types.h"
#include "host/bvh/big_array.h"
#include "host/render/render_settings.h"
#include "host/scene/scene.h"

namespace gc {

struct DeviceTextures {
    std::vector<dev::GcTexture> textures;  // the views of texture_views
    std::vector<std::uint32_t> texels;
};

// The device's texture views. View i < scene.textures.size() is scene texture i untransformed
// (so a scene without uv transforms uploads what it always did); after them, one view per
// distinct (texture, non-identity transform) pair that a material slot reads, in order of
// first use, sharing its texture's texels. Materials index views (one per MaterialSlot;
// GC_INVALID = no texture). make_materials and make_textures both read this one table, so
// their indices agree.
enum MaterialSlot : std::size_t {
    kSlotAlbedo, kSlotMetallicRoughness, kSlotNormal, kSlotEmission,
    kSlotClearcoat, kSlotClearcoatRoughness, kSlotSpecular, kSlotSpecularColor, kSlotSheenColor, kSlotSheenRoughness,
    kSlotTransmission, kSlotClearcoatNormal, kMaterialSlots
};
struct TextureViews {
    std::vector<dev::GcTexture> views;
    std::vector<std::array<std::uint32_t, kMaterialSlots>> material_slots;  // one per scene material
};
TextureViews texture_views(const Scene& scene);

// The affine map of a slot's uv transform: rows (a, b, c) and (d, e, f) with
// u' = a u + b v + c, v' = d u + e v + f, i.e. T(offset) R(rotation) S(scale) as glTF's
// KHR_texture_transform defines it (rotation turns the uvs counter-clockwise in glTF's
// uv space, whose v points down the image).
std::array<glm::vec3, 2> uv_transform_rows(const UvTransform& t);

// One GcTriangleAttribs per scene triangle, in scene order. Large scenes fill it in parallel
// chunks, into a BigArray (on huge pages, written once), because CPU devices read it in place
// (cl::Buffer::over_host): for a scene of millions of triangles it is hundreds of MB, and a
// serial fill plus a driver copy would be seconds of the time to first image
// (docs/decisions/host-memory-in-place.md).
BigArray<dev::GcTriangleAttribs> make_triangle_attribs(const Scene& scene);
std::vector<dev::GcMaterial> make_materials(const Scene& scene);
DeviceTextures make_textures(const Scene& scene);
std::vector<dev::GcPointLight> make_point_lights(const Scene& scene);

// Emissive triangles with power-proportional selection probabilities (power = area times
// the luminance of the emitted radiance). Zero-area emitters are left out: they can never
// be hit nor sampled. The last cdf is exactly 1. Only triangles from `first_triangle` on
// are considered (an instanced scene's world-space emitters, DeviceScene::upload_instanced).
std::vector<dev::GcEmitter> make_emitters(const Scene& scene, std::uint32_t first_triangle = 0);

// Sum over emitters of area * luminance(emission): the normalisation of the light pdf the
// kernels compute (gc_light_pdf_w), consistent with make_emitters' selection probabilities.
float total_emitter_power(const Scene& scene);
// The same for the emitters make_emitters(scene) made, without making them again.
float total_emitter_power(const Scene& scene, std::span<const dev::GcEmitter> emitters);

// What the kernels' parameter block says about a scene: its counts and the light pdf's
// normalisation. Kept by a device scene, so that a render needs no host scene.
struct SceneSummary {
    std::uint32_t triangles = 0;
    std::uint32_t emitters = 0;  // zero-area emitters dropped, as make_emitters drops them
    std::uint32_t point_lights = 0;
    std::uint32_t textures = 0;
    float emitter_power = 0.0f;  // total_emitter_power
};
SceneSummary summarize(const Scene& scene);
// The same from the emitters and texture views already made for an upload.
SceneSummary summarize(const Scene& scene, std::span<const dev::GcEmitter> emitters, std::size_t texture_views);

// The kernels' parameter block for a whole-image pass; the renderer then sets the batch
// (pixel_offset/pixel_count) and sample_index per pass. Shared by the OpenCL and Vulkan paths.
dev::GcRenderParams make_render_params(const SceneSummary& scene, const Camera& camera, const RenderSettings& settings);
dev::GcRenderParams make_render_params(const Scene& scene, const Camera& camera, const RenderSettings& settings);

// Points `params` at the environment map of settings.env_map_path, uploaded as width x height
// texels: the texels are then the radiance and env_radiance scales them (1 unless
// --env-scale), and a black map (uploaded as 0 x 0) leaves the environment black. Without a
// map `params` keeps the constant env_radiance.
void set_environment_map(dev::GcRenderParams& params, const RenderSettings& settings, std::uint32_t width,
                         std::uint32_t height);

// Pinhole camera for a width x height image (square pixels, vertical field of view).
dev::GcCamera make_camera(const Camera& camera, int width, int height);

}  // namespace gc
