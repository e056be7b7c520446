// The mesh render pass on Vulkan: the scene's flat triangle array rasterised (one draw) with
// the ray tracer's camera into a G-buffer — shaded preview, shading normal, albedo, depth
// as distance along the pixel-centre ray, primitive id — read back to the host. Headless:
// offscreen images, no window, no surface.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "host/image/film.h"
#include "host/render/render_settings.h"
#include "host/scene/scene.h"
#include "host/vk/context.h"
#include "host/vk/handle.h"
#include "host/vk/pipeline.h"
#include "host/vk/scene_buffers.h"

namespace gc::vk {

// Row-major, row 0 = top, width * height entries each.
struct GBuffer {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    Film preview;                    // albedo under a headlight + clamped emission (gc_aov_preview)
    std::vector<float> depth;        // distance along the pixel-centre camera ray; 0 where empty
    std::vector<glm::vec3> normal;   // unit shading normal; 0 where empty
    std::vector<glm::vec3> albedo;   // diffuse reflectance after texturing; 0 where empty
    std::vector<std::int32_t> primid; // scene triangle index; -1 where empty
};

class RasterPass {
public:
    // Uses settings.width, height and env_radiance (the preview's background).
    RasterPass(const Context& context, const Scene& scene, const Camera& camera, const RenderSettings& settings);
    ~RasterPass();
    RasterPass(const RasterPass&) = delete;
    RasterPass& operator=(const RasterPass&) = delete;

    // Renders one frame and reads it back.
    GBuffer render();

private:
    struct Target {
        Image image;
        Memory memory;
        ImageView view;
    };
    Target make_target(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, const char* name);
    void make_pipeline();

    const Context& m_context;
    std::uint32_t m_width;
    std::uint32_t m_height;
    std::uint32_t m_vertex_count;
    float m_near;
    glm::vec3 m_background;
    SceneBuffers m_scene;
    StorageBufferSet m_set;
    PipelineLayout m_layout;
    RenderPass m_render_pass;
    Pipeline m_pipeline;
    Target m_color[4]; // preview, normal+depth, albedo, primid
    Target m_depth;
    Framebuffer m_framebuffer;
    Buffer m_readback[4];
    Buffer m_unused_film;
};

}  // namespace gc::vk
