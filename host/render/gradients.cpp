#include "host/render/gradients.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "gc_grad_slots.h"
#include "host/render/integrator.h"
#include "host/render/scene_convert.h"
#include "host/render/scene_params.h"
#include "host/util/error.h"

namespace gc {
namespace {

// The most contributions one slot can receive per sample and vertex: a material's base colour
// one, its emission one from a hit and one as the light of next-event estimation, the
// environment the same two, a texel four (a lookup's four taps may all be that texel).
constexpr double k_contributions_per_vertex = 4.0;

// The fewest paths (pixels x spp) for which PrimalPass::Auto traces the radiance in a wavefront
// pass: a smaller pass leaves the wavefront's per-bounce launches too little work to pay for
// themselves (measured on GPUs at both sides of it: docs/performance.md, "Gradients").
constexpr std::uint64_t k_wavefront_primal_paths = std::uint64_t(1) << 20;

// Slots hold 64-bit signed sums; the scale keeps every possible sum within 2^62.
constexpr double k_slot_limit = 4611686018427387904.0;  // 2^62

// The exponent e for which count contributions of at most `bound` each sum below the limit.
int scale_exponent(double bound, double count)
{
    if (!(bound > 0.0)) return 0;
    const int e = static_cast<int>(std::floor(std::log2(k_slot_limit / (bound * count))));
    return std::clamp(e, -120, 120);
}

// The slots of each parameter asked for; texels get theirs after the environment's, only for
// the textures asked for.
struct SlotLayout {
    std::uint32_t env_slot = 0;
    std::uint32_t count = 0;
    std::vector<std::uint32_t> texture_slots;  // per scene texture: its first slot, or GC_INVALID
    std::vector<std::uint32_t> view_slots;     // per device texture view: its texture's first slot
};

SlotLayout slot_layout(const Scene& scene, std::span<const ParamRef> refs)
{
    SlotLayout layout;
    layout.env_slot = static_cast<std::uint32_t>(scene.materials.size()) * GC_GRAD_MATERIAL_STRIDE;
    layout.count = layout.env_slot + GC_GRAD_ENV_SLOTS;
    layout.texture_slots.assign(scene.textures.size(), GC_INVALID);
    for (const ParamRef& ref : refs) {
        if (ref.kind != ParamRef::Kind::Texels || layout.texture_slots[ref.texture] != GC_INVALID)
            continue;
        const Texture& t = scene.textures[ref.texture];
        layout.texture_slots[ref.texture] = layout.count;
        layout.count +=
            4u * static_cast<std::uint32_t>(t.width) * static_cast<std::uint32_t>(t.height);
    }
    // View i < textures.size() is texture i; later views (uv transforms) share a texture's texels.
    const std::vector<dev::GcTexture> views = texture_views(scene).views;
    layout.view_slots.assign(std::max<std::size_t>(views.size(), 1), GC_INVALID);
    for (std::size_t v = 0; v < views.size(); ++v)
        for (std::size_t t = 0; t < scene.textures.size(); ++t)
            if (views[t].offset == views[v].offset) {
                layout.view_slots[v] = layout.texture_slots[t];
                break;
            }
    return layout;
}

std::vector<std::uint32_t> material_slots(std::uint32_t material, std::uint32_t field,
                                          std::uint32_t count)
{
    std::vector<std::uint32_t> slots;
    for (std::uint32_t i = 0; i < count; ++i)
        slots.push_back(material * GC_GRAD_MATERIAL_STRIDE + field + i);
    return slots;
}

std::vector<std::uint32_t> slots_of(const ParamRef& ref, const SlotLayout& layout,
                                    const Scene& scene)
{
    const std::uint32_t env_slot = layout.env_slot;
    switch (ref.kind) {
        case ParamRef::Kind::Texels: {
            const Texture& t = scene.textures[ref.texture];
            std::vector<std::uint32_t> slots(4u * static_cast<std::size_t>(t.width) *
                                             static_cast<std::size_t>(t.height));
            for (std::size_t i = 0; i < slots.size(); ++i)
                slots[i] = layout.texture_slots[ref.texture] + static_cast<std::uint32_t>(i);
            return slots;
        }
        case ParamRef::Kind::BaseColor:
            return material_slots(ref.material, GC_GRAD_FIELD_BASE_COLOR, 3);
        case ParamRef::Kind::Emission:
            return material_slots(ref.material, GC_GRAD_FIELD_EMISSION, 3);
        case ParamRef::Kind::Specular:
            return material_slots(ref.material, GC_GRAD_FIELD_SPECULAR, 3);
        case ParamRef::Kind::PhongExponent:
            return material_slots(ref.material, GC_GRAD_FIELD_PHONG_EXPONENT, 1);
        case ParamRef::Kind::Metallic:
            return material_slots(ref.material, GC_GRAD_FIELD_METALLIC, 1);
        case ParamRef::Kind::Roughness:
            return material_slots(ref.material, GC_GRAD_FIELD_ROUGHNESS, 1);
        case ParamRef::Kind::EnvRadiance:
            return {env_slot, env_slot + 1, env_slot + 2};
    }
    return {};
}

// Samples per work-item: as asked (0: all of a pixel's on CPUs, one on GPUs), but never so few
// that the items' count leaves 32 bits (the kernel's item index).
std::uint32_t samples_per_item(std::uint32_t asked, bool gpu, std::uint32_t pixels, std::uint32_t spp)
{
    std::uint32_t per = asked != 0 ? std::min(asked, spp) : (gpu ? 1u : spp);
    const std::uint64_t max_runs = std::max<std::uint64_t>(1, (std::uint64_t(1) << 31) / pixels);
    return std::max<std::uint32_t>(per, static_cast<std::uint32_t>((spp + max_runs - 1) / max_runs));
}

}  // namespace

// An optimiser calls backward once per step with the same sizes: its buffers stay allocated
// between calls (a release and an allocation per call cost a GPU's driver time), made anew
// only when a size changes.
template <class T>
cl::Buffer<T>& PathAdjoint::sized(cl::Buffer<T>& buffer, std::size_t count, cl_mem_flags flags, const char* name)
{
    if (!buffer || buffer.count() != count) buffer = cl::Buffer<T>::create(m_context, count, flags, name);
    return buffer;
}

PathAdjoint::PathAdjoint(const Renderer& renderer, AdjointOptions options)
    : m_context(renderer.context()),
      m_options(options)
{
    build(renderer);
}

void PathAdjoint::build(const Renderer& renderer)
{
    const DeviceScene& scene = renderer.device_scene();
    std::string options = scene_program_options(scene);
    if (m_options.atomics == SlotAtomics::Split32) options += " -D GC_GRAD_SPLIT_ATOMICS";
    m_program =
        std::make_unique<cl::Program>(m_context, "adjoint.cl", options, renderer.setup().build);
    m_kernel = m_program->kernel("path_adjoint");
    m_features = scene.features;
    m_renderer_wavefront = !path_megakernel_for(m_context.device(), renderer.setup().tuning.path_kernel);
    // Made by the first backward pass that wants it, sized for its sample count (the renderer's
    // settings.spp may be far more, and its path slots take device memory); its program is the
    // renderer's wavefront.cl, built already and taken from the program cache.
    m_primal.reset();
    if (!m_no_primal) m_no_primal = cl::Buffer<dev::GcPathState>::create(m_context, 1, CL_MEM_READ_ONLY, "no primal paths");
}

bool PathAdjoint::wavefront_primal(std::uint64_t paths) const
{
    switch (m_options.primal) {
    case PrimalPass::InKernel: return false;
    case PrimalPass::Wavefront: return true;
    case PrimalPass::Auto: break;
    }
    return m_renderer_wavefront && paths >= k_wavefront_primal_paths;
}

WavefrontPathIntegrator& PathAdjoint::primal_integrator(const Renderer& renderer, std::uint32_t spp)
{
    if (m_primal && m_primal_spp == spp) return *m_primal;
    m_primal.reset();
    // Path slots for every pixel's spp samples, up to the wavefront's size (path_capacity).
    RenderSettings settings = renderer.settings();
    settings.spp = spp;
    m_primal = std::make_unique<WavefrontPathIntegrator>(m_context, renderer.device_scene(), settings, renderer.setup(),
                                                         renderer.batch_pixels());
    m_primal_spp = spp;
    // Its passes accumulate into a film of their own, never read: the renderer's stays as it was.
    const std::size_t pixels = std::size_t(settings.width) * std::size_t(settings.height);
    m_primal_film.sums = cl::Buffer<glm::vec4>::create(m_context, pixels, CL_MEM_READ_WRITE, "primal film sums");
    m_primal_film.squares = cl::Buffer<glm::vec4>::create(m_context, pixels, CL_MEM_READ_WRITE, "primal film squares");
    m_primal_film.pixel_list = cl::Buffer<std::uint32_t>::create(m_context, 1, CL_MEM_READ_ONLY, "primal pixel list");
    return *m_primal;
}

Gradients PathAdjoint::backward(const Renderer& renderer, const Scene& host_scene,
                                std::span<const glm::vec4> loss_grad,
                                std::span<const std::string> params, std::uint32_t spp,
                                std::uint32_t seed)
{
    const DeviceScene& scene = renderer.device_scene();
    std::vector<ParamRef> refs;
    for (const std::string& name : params) refs.push_back(resolve_param(host_scene, name));
    const RenderSettings& settings = renderer.settings();
    const std::uint32_t width = static_cast<std::uint32_t>(settings.width);
    const std::uint32_t height = static_cast<std::uint32_t>(settings.height);
    const std::uint32_t pixels = width * height;
    if (loss_grad.size() != pixels)
        throw UsageError("the loss gradient has " + std::to_string(loss_grad.size()) +
                         " pixels, the image " + std::to_string(pixels) + " (" +
                         std::to_string(width) + " x " + std::to_string(height) + ")");
    if (spp == 0) throw UsageError("a backward pass needs at least one sample per pixel");
    if (settings.integrator != IntegratorKind::Path)
        throw UsageError(
            std::string("gradients are of the path integrator's image; this renderer runs '") +
            integrator_name(settings.integrator) + "'");
    if (scene.features != m_features) build(renderer);

    if (host_scene.materials.size() != scene.materials.count() ||
        host_scene.triangle_count() != scene.triangle_count)
        throw UsageError("backward needs the host scene the renderer's device scene was made from");
    const SlotLayout layout = slot_layout(host_scene, refs);
    const std::uint32_t slot_count = layout.count;
    cl::Buffer<std::uint32_t>& view_slots =
        sized(m_view_slots, layout.view_slots.size(), CL_MEM_READ_ONLY, "texel gradient slots");
    view_slots.write(layout.view_slots);
    // Bit i: material or environment slot i was asked for (gc_grad_slots.h).
    const std::uint32_t texel_slot = layout.env_slot + GC_GRAD_ENV_SLOTS;
    std::vector<std::uint32_t> wanted_bits((texel_slot + 31) / 32, 0u);
    for (const ParamRef& ref : refs)
        if (ref.kind != ParamRef::Kind::Texels)
            for (std::uint32_t s : slots_of(ref, layout, host_scene)) wanted_bits[s / 32] |= 1u << (s % 32);
    cl::Buffer<std::uint32_t>& wanted = sized(m_wanted, wanted_bits.size(), CL_MEM_READ_ONLY, "gradients asked for");
    wanted.write(wanted_bits);

    // Each sample's share of d loss / d (pixel mean).
    std::vector<glm::vec4> per_sample(pixels);
    double max_delta = 0.0;
    for (std::uint32_t i = 0; i < pixels; ++i) {
        per_sample[i] = glm::vec4(glm::vec3(loss_grad[i]) / static_cast<float>(spp), 0.0f);
        for (int c = 0; c < 3; ++c)
            max_delta = std::max(max_delta, std::fabs(static_cast<double>(per_sample[i][c])));
    }
    cl::Buffer<glm::vec4>& deltas = sized(m_deltas, pixels, CL_MEM_READ_ONLY, "loss gradient");
    deltas.write(per_sample);
    cl::Buffer<std::uint64_t>& slots = sized(m_slots, slot_count, CL_MEM_READ_WRITE, "gradient slots");
    cl::Buffer<std::uint32_t>& max_bits = sized(m_max_bits, 1, CL_MEM_READ_WRITE, "largest contribution");

    dev::GcRenderParams p = make_render_params(scene.summary, renderer.camera(), settings);
    set_environment_map(p, settings, scene.env_width, scene.env_height);
    p.seed = seed;
    p.sample_index = 0;
    p.samples_in_pass = spp;
    p.pixel_offset = 0;
    p.pixel_count = pixels;
    p.pixels_per_item = 1;

    // The first guess bounds a vertex's contribution by 256 times the largest delta (radiance
    // times BSDF factors rarely exceed it); the pass records the true largest, and if the
    // guess was short the pass runs again with that: either way a function of the inputs only.
    const double count = static_cast<double>(pixels) * spp * std::max(settings.max_depth, 1u) *
                         k_contributions_per_vertex;
    double bound = max_delta * 256.0;
    // One work-item per group on CPUs, as the megakernel (megakernel_path.cpp says why).
    const bool gpu = m_context.device().is_gpu;
    const std::size_t local_size = gpu ? 0 : 1;
    // The adjoint's launches: one over every pixel and sample where it traces L itself; where
    // the wavefront traces it, one after each of the wavefront's batches (as many samples of
    // as many pixels as its path slots hold), reading that batch's paths.
    WavefrontPathIntegrator* primal =
        wavefront_primal(std::uint64_t(pixels) * spp) ? &primal_integrator(renderer, spp) : nullptr;
    const std::uint32_t batch_pixels = primal ? std::min(pixels, renderer.batch_pixels()) : pixels;
    const std::uint32_t pass_samples = primal ? std::min(spp, primal->max_samples_per_pass(batch_pixels)) : spp;
    const auto launch_adjoint = [&](const dev::GcRenderParams& batch, const cl::Buffer<dev::GcPathState>& paths,
                                    float scale) {
        const std::uint32_t per_item =
            samples_per_item(m_options.samples_per_item, gpu, batch.pixel_count, batch.samples_in_pass);
        const std::size_t items =
            std::size_t(batch.pixel_count) * ((batch.samples_in_pass + per_item - 1) / per_item);
        m_kernel.set_args(batch, scene.scene_args(), deltas, slots, max_bits, view_slots, wanted, paths,
                          primal ? 1u : 0u, scale, layout.env_slot, slot_count,
                          static_cast<std::uint32_t>(layout.view_slots.size()), per_item);
        m_kernel.launch(m_context, items, local_size, "adjoint paths");
    };
    std::vector<std::uint64_t> sums(slot_count, 0);
    m_stats = {};
    for (int attempt = 0; attempt < 2; ++attempt) {
        const int e = scale_exponent(bound, count);
        const std::vector<std::uint64_t> zeros(slot_count, 0);
        slots.write(zeros);
        const std::uint32_t zero = 0;
        max_bits.write(std::span<const std::uint32_t>(&zero, 1));
        const float scale = std::ldexp(1.0f, e);
        if (max_delta > 0.0 && primal) {
            for (std::uint32_t first = 0; first < spp; first += pass_samples)
                for (std::uint32_t offset = 0; offset < pixels; offset += batch_pixels) {
                    dev::GcRenderParams batch = p;
                    batch.sample_index = first;
                    batch.samples_in_pass = std::min(pass_samples, spp - first);
                    batch.pixel_offset = offset;
                    batch.pixel_count = std::min(batch_pixels, pixels - offset);
                    primal->render_batch(batch, scene, m_primal_film);
                    launch_adjoint(batch, primal->paths(), scale);
                }
        } else if (max_delta > 0.0) {
            launch_adjoint(p, m_no_primal, scale);
        }
        m_context.finish();
        if (primal && max_delta > 0.0) primal->end_pass();
        std::uint32_t bits = 0;
        max_bits.read(std::span<std::uint32_t>(&bits, 1));
        if (bits == GC_GRAD_OUT_OF_RANGE)
            throw DeviceError("the adjoint addressed a gradient slot out of range on " + m_context.device().device_name +
                              " (" + std::to_string(slot_count) + " slots, " +
                              std::to_string(layout.view_slots.size()) + " texture views): a bug; nothing was written there");
        float largest = 0.0f;
        std::memcpy(&largest, &bits, sizeof largest);
        m_stats.scale_exponent = e;
        m_stats.max_contribution = largest;
        m_stats.rescaled = attempt > 0;
        if (static_cast<double>(largest) <= bound) {
            slots.read(sums);
            break;
        }
        if (attempt == 1) throw DeviceError("the gradient's fixed-point sums would overflow");
        bound = largest;
    }

    Gradients out;
    for (std::size_t i = 0; i < params.size(); ++i) {
        std::vector<float> g;
        for (std::uint32_t s : slots_of(refs[i], layout, host_scene))
            g.push_back(static_cast<float>(std::ldexp(
                static_cast<double>(static_cast<std::int64_t>(sums[s])), -m_stats.scale_exponent)));
        out[params[i]] = std::move(g);
    }
    return out;
}

}  // namespace gc
