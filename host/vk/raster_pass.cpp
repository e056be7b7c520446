#include "host/vk/raster_pass.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "host/util/error.h"
#include "host/vk/shaders.h"
#include "host/vk/vk_error.h"
#include "kernels/vk/bindings.h"

namespace gc::vk {
namespace {

constexpr VkFormat kColorFormats[4] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT,
                                       VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32_SINT};
constexpr std::uint32_t kTexelBytes[4] = {16, 16, 16, 4};
constexpr const char* kColorNames[4] = {"preview", "normal+depth", "albedo", "primitive id"};
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Near plane of the reversed infinite projection: small against the scene's size and the
// camera's distance, so no surface the ray tracer sees (t_min = 0) is clipped in practice.
float near_plane(const Scene& scene, const Camera& camera)
{
    const Bounds3 b = scene.bounds();
    float extent = 1.0f;
    if (!b.empty()) extent = length(b.diagonal()) + length(camera.look_from - b.centroid());
    return std::isfinite(extent) && extent > 0.0f ? 1e-6f * extent : 1e-6f;
}

}  // namespace

RasterPass::RasterPass(const Context& context, const Scene& scene, const Camera& camera, const RenderSettings& settings)
    : m_context(context),
      m_width(static_cast<std::uint32_t>(settings.width)),
      m_height(static_cast<std::uint32_t>(settings.height)),
      m_vertex_count(static_cast<std::uint32_t>(3 * scene.triangle_count())),
      m_near(near_plane(scene, camera)),
      m_background(settings.env_radiance),
      m_scene(SceneBuffers::upload(context, scene, nullptr, camera, settings)),
      m_set(context, GC_VK_BINDING_COUNT, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT)
{
    // The film binding is compute-only, but every binding of the set must be valid.
    m_unused_film = Buffer(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "unused film");
    m_scene.bind(m_set);
    m_set.bind(GC_VK_BINDING_FILM, m_unused_film);

    for (int i = 0; i < 4; ++i) {
        VkFormatProperties fp{};
        vkGetPhysicalDeviceFormatProperties(context.physical_device(), kColorFormats[i], &fp);
        if ((fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) == 0)
            throw DeviceError("Vulkan device '" + context.info().name + "' cannot render to the " + kColorNames[i] +
                              " format");
        m_color[i] = make_target(kColorFormats[i], VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT, kColorNames[i]);
        m_readback[i] = Buffer(context, VkDeviceSize(m_width) * m_height * kTexelBytes[i],
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               std::string(kColorNames[i]) + " readback");
    }
    VkFormatProperties dp{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), kDepthFormat, &dp);
    if ((dp.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) == 0)
        throw DeviceError("Vulkan device '" + context.info().name + "' has no 32-bit float depth buffer");
    m_depth = make_target(kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, "depth");
    make_pipeline();
}

RasterPass::~RasterPass() = default;

RasterPass::Target RasterPass::make_target(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                                           const char* name)
{
    const std::string what = std::string("allocating the ") + name + " image (" + std::to_string(m_width) + "x" +
                             std::to_string(m_height) + ")";
    const VkDevice device = m_context.device();
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = format;
    ici.extent = {m_width, m_height, 1};
    ici.mipLevels = 1;
    ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = usage;
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    Target t;
    VkImage image = VK_NULL_HANDLE;
    check(vkCreateImage(device, &ici, nullptr, &image), "vkCreateImage", what);
    t.image = Image(device, image);

    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = m_context.memory_type(req.memoryTypeBits, 0, std::string("the ") + name + " image");
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &mai, nullptr, &memory), "vkAllocateMemory", what);
    t.memory = Memory(device, memory);
    check(vkBindImageMemory(device, image, memory, 0), "vkBindImageMemory", what);

    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format;
    vci.subresourceRange = {aspect, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(device, &vci, nullptr, &view), "vkCreateImageView", what);
    t.view = ImageView(device, view);
    return t;
}

void RasterPass::make_pipeline()
{
    const VkDevice device = m_context.device();

    // Render pass: four colour targets left ready for the copy to the host, one depth target.
    std::array<VkAttachmentDescription, 5> attachments{};
    std::array<VkAttachmentReference, 4> color_refs{};
    for (std::uint32_t i = 0; i < 5; ++i) {
        VkAttachmentDescription& a = attachments[i];
        a.format = i < 4 ? kColorFormats[i] : kDepthFormat;
        a.samples = VK_SAMPLE_COUNT_1_BIT;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.storeOp = i < 4 ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        a.finalLayout = i < 4 ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        if (i < 4) color_refs[i] = {i, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    }
    const VkAttachmentReference depth_ref{4, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 4;
    subpass.pColorAttachments = color_refs.data();
    subpass.pDepthStencilAttachment = &depth_ref;
    // The colour writes must be visible to the copies recorded after the pass.
    VkSubpassDependency dependency{};
    dependency.srcSubpass = 0;
    dependency.dstSubpass = VK_SUBPASS_EXTERNAL;
    dependency.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependency.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpci.attachmentCount = static_cast<std::uint32_t>(attachments.size());
    rpci.pAttachments = attachments.data();
    rpci.subpassCount = 1;
    rpci.pSubpasses = &subpass;
    rpci.dependencyCount = 1;
    rpci.pDependencies = &dependency;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    check(vkCreateRenderPass(device, &rpci, nullptr, &render_pass), "vkCreateRenderPass", "creating the G-buffer pass");
    m_render_pass = RenderPass(device, render_pass);

    std::array<VkImageView, 5> views{m_color[0].view.get(), m_color[1].view.get(), m_color[2].view.get(),
                                     m_color[3].view.get(), m_depth.view.get()};
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = render_pass;
    fci.attachmentCount = static_cast<std::uint32_t>(views.size());
    fci.pAttachments = views.data();
    fci.width = m_width;
    fci.height = m_height;
    fci.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    check(vkCreateFramebuffer(device, &fci, nullptr, &framebuffer), "vkCreateFramebuffer", "creating the G-buffer");
    m_framebuffer = Framebuffer(device, framebuffer);

    m_layout = make_pipeline_layout(m_context, m_set, sizeof(float), VK_SHADER_STAGE_VERTEX_BIT);
    const ShaderModule vert = make_shader_module(m_context, shaders::raster_vert(), "raster.vert");
    const ShaderModule frag = make_shader_module(m_context, shaders::raster_frag(), "raster.frag");
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT,
                 vert.get(), "main", nullptr};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT,
                 frag.get(), "main", nullptr};

    // No vertex buffers: the vertex shader reads positions from a storage buffer.
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    const VkViewport viewport{0.0f, 0.0f, static_cast<float>(m_width), static_cast<float>(m_height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {m_width, m_height}};
    VkPipelineViewportStateCreateInfo viewport_state{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport_state.viewportCount = 1;
    viewport_state.pViewports = &viewport;
    viewport_state.scissorCount = 1;
    viewport_state.pScissors = &scissor;
    // Triangles are two-sided for the ray tracer too: no culling.
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    // Reversed depth (see raster.vert): nearer is greater.
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_GREATER;
    std::array<VkPipelineColorBlendAttachmentState, 4> blend{};
    for (auto& b : blend)
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo color_blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    color_blend.attachmentCount = static_cast<std::uint32_t>(blend.size());
    color_blend.pAttachments = blend.data();

    VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gci.stageCount = static_cast<std::uint32_t>(stages.size());
    gci.pStages = stages.data();
    gci.pVertexInputState = &vertex_input;
    gci.pInputAssemblyState = &assembly;
    gci.pViewportState = &viewport_state;
    gci.pRasterizationState = &raster;
    gci.pMultisampleState = &multisample;
    gci.pDepthStencilState = &depth;
    gci.pColorBlendState = &color_blend;
    gci.layout = m_layout.get();
    gci.renderPass = render_pass;
    gci.subpass = 0;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &gci, nullptr, &pipeline), "vkCreateGraphicsPipelines",
          "building the raster pipeline");
    m_pipeline = Pipeline(device, pipeline);
}

GBuffer RasterPass::render()
{
    m_context.submit_and_wait(
        [&](VkCommandBuffer cmd) {
            std::array<VkClearValue, 5> clears{};
            clears[0].color.float32[0] = m_background.x;
            clears[0].color.float32[1] = m_background.y;
            clears[0].color.float32[2] = m_background.z;
            clears[0].color.float32[3] = 1.0f;
            clears[3].color.int32[0] = -1;
            clears[4].depthStencil = {0.0f, 0};
            VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
            rbi.renderPass = m_render_pass.get();
            rbi.framebuffer = m_framebuffer.get();
            rbi.renderArea = {{0, 0}, {m_width, m_height}};
            rbi.clearValueCount = static_cast<std::uint32_t>(clears.size());
            rbi.pClearValues = clears.data();
            vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_pipeline.get());
            const VkDescriptorSet set = m_set.set();
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout.get(), 0, 1, &set, 0, nullptr);
            vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof m_near, &m_near);
            if (m_vertex_count > 0) vkCmdDraw(cmd, m_vertex_count, 1, 0, 0);
            vkCmdEndRenderPass(cmd);

            for (int i = 0; i < 4; ++i) {
                VkBufferImageCopy region{};
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageExtent = {m_width, m_height, 1};
                vkCmdCopyImageToBuffer(cmd, m_color[i].image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                       m_readback[i].get(), 1, &region);
            }
            VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                                 nullptr, 0, nullptr);
        },
        "rendering the G-buffer");

    const std::size_t n = std::size_t(m_width) * m_height;
    std::vector<glm::vec4> preview(n), normal_depth(n), albedo(n);
    GBuffer g;
    g.width = m_width;
    g.height = m_height;
    g.primid.resize(n);
    m_readback[0].read(preview.data(), n * sizeof(glm::vec4));
    m_readback[1].read(normal_depth.data(), n * sizeof(glm::vec4));
    m_readback[2].read(albedo.data(), n * sizeof(glm::vec4));
    m_readback[3].read(g.primid.data(), n * sizeof(std::int32_t));
    g.preview = Film(m_width, m_height);
    g.depth.resize(n);
    g.normal.resize(n);
    g.albedo.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto x = static_cast<std::uint32_t>(i % m_width);
        const auto y = static_cast<std::uint32_t>(i / m_width);
        g.preview.set(x, y, Rgba{preview[i].x, preview[i].y, preview[i].z, 1.0f});
        g.normal[i] = glm::vec3(normal_depth[i]);
        g.depth[i] = normal_depth[i].w;
        g.albedo[i] = glm::vec3(albedo[i]);
    }
    return g;
}

}  // namespace gc::vk
