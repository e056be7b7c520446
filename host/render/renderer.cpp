#include "host/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "host/render/chunks.h"
#include "host/render/environment.h"
#include "host/render/scene_convert.h"
#include "host/render/wavefront_path.h"
#include "host/util/error.h"
#include "host/util/log.h"

namespace gc {
namespace {

std::shared_ptr<const DeviceScene> upload_alone(const cl::Context& context, const Scene& scene, const FlatBvh& bvh,
                                                const RenderSettings& settings, const DeviceTuning& tuning)
{
    return std::make_shared<const DeviceScene>(
        DeviceScene::upload(context, scene, bvh, load_environment_map(settings), tuning));
}

// Pixels per kernel batch: the wavefront's size (RenderSettings::wavefront_size, or the
// device's default), or the whole image if it is smaller.
std::uint32_t batch_pixels_for(const cl::DeviceInfo& device, const RenderSettings& settings)
{
    const std::uint32_t pixels = static_cast<std::uint32_t>(settings.width) * static_cast<std::uint32_t>(settings.height);
    const std::uint32_t wavefront = settings.wavefront_size ? settings.wavefront_size : default_wavefront_size(device);
    return std::min(pixels, wavefront);
}

cl::Buffer<glm::vec4> film_buffer(const cl::Context& context, std::uint32_t pixels, const char* name)
{
    return cl::Buffer<glm::vec4>::create(context, pixels, CL_MEM_READ_WRITE, name);
}

}  // namespace

Renderer::Renderer(const cl::Context& context, std::shared_ptr<const DeviceScene> scene, const Camera& camera,
                   const RenderSettings& settings, const RenderSetup& setup)
    : m_context(context),
      m_scene(std::move(scene)),
      m_scene_revision(m_scene->revision),
      m_program_features(m_scene->features),
      m_settings(settings),
      m_setup(setup),
      m_camera(camera),
      m_batch_pixels(batch_pixels_for(context.device(), settings)),
      m_integrator(make_integrator(context, *m_scene, settings, setup, m_batch_pixels)),
      m_planner(settings.samples_per_pass)
{
    if (settings.env_map_path != m_scene->env_source)
        throw UsageError("the render asks for the environment map '" + settings.env_map_path +
                         "' but the device scene was uploaded with '" + m_scene->env_source + "'");
    update_params();
    const std::uint32_t pixels = m_params.width * m_params.height;
    m_film.sums = film_buffer(context, pixels, "film");
    m_film.squares = film_buffer(context, pixels, "film squares");
    // A placeholder until select_pixels: the path kernels take the list either way.
    m_film.pixel_list = cl::Buffer<std::uint32_t>::create(context, 1, CL_MEM_READ_ONLY, "pixel list");
    clear();
}

Renderer::Renderer(const cl::Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                   const RenderSettings& settings, const RenderSetup& setup)
    : Renderer(context, upload_alone(context, scene, bvh, settings, setup.tuning), camera, settings, setup)
{
}

Renderer::~Renderer() = default;

void Renderer::clear(std::uint32_t next_sample)
{
    const glm::vec4 zero(0.0f);
    for (const cl::Buffer<glm::vec4>* film : {&m_film.sums, &m_film.squares})
        GC_CL_WHAT("clearing the film", clEnqueueFillBuffer, m_context.queue(), film->mem(), &zero, sizeof zero, 0,
                   film->bytes(), 0, nullptr, nullptr);
    m_sample_count = 0;
    m_next_sample = next_sample;
}

void Renderer::set_camera(const Camera& camera)
{
    m_camera = camera;
    update_params();
    clear();
}

void Renderer::set_env_radiance(const glm::vec3& radiance)
{
    m_settings.env_radiance = radiance;
    update_params();
    clear();
}

void Renderer::select_pixels(std::vector<std::uint32_t> pixels)
{
    if (m_settings.integrator != IntegratorKind::Path)
        throw UsageError(std::string("only the path integrator renders selected pixels, not ") +
                         integrator_name(m_settings.integrator));
    const std::uint32_t image = m_params.width * m_params.height;
    for (std::size_t i = 0; i < pixels.size(); ++i)
        if (pixels[i] >= image || (i > 0 && pixels[i] <= pixels[i - 1]))
            throw UsageError("selected pixels must be strictly ascending indices below " + std::to_string(image) +
                             " (entry " + std::to_string(i) + " is " + std::to_string(pixels[i]) + ")");
    if (m_film.pixel_list.count() < std::max<std::size_t>(pixels.size(), 1))
        m_film.pixel_list = cl::Buffer<std::uint32_t>::create(m_context, image, CL_MEM_READ_ONLY, "pixel list");
    m_film.pixel_list.write(pixels);
    m_pixel_list = std::move(pixels);
    m_pixels_listed = true;
    clear(m_next_sample);
}

void Renderer::select_all_pixels()
{
    m_pixel_list.clear();
    m_pixels_listed = false;
    clear(m_next_sample);
}

void Renderer::follow_scene_updates()
{
    if (m_scene->revision == m_scene_revision) return;
    m_scene_revision = m_scene->revision;
    if (m_scene->features != m_program_features) {
        log_verbose("the scene's kernel features changed: rebuilding the " +
                    std::string(integrator_name(m_settings.integrator)) + " program");
        m_integrator = make_integrator(m_context, *m_scene, m_settings, m_setup, m_batch_pixels);
        m_program_features = m_scene->features;
    }
    update_params();
    clear();
}

void Renderer::update_params()
{
    m_params = make_render_params(m_scene->summary, m_camera, m_settings);
    set_environment_map(m_params, m_settings, m_scene->env_width, m_scene->env_height);
}

void Renderer::render(std::uint32_t first_sample, std::uint32_t count)
{
    follow_scene_updates();
    m_next_sample = first_sample;
    for (std::uint32_t done = 0; done < count;) done += render_samples(count - done);
}

std::uint32_t Renderer::render_samples(std::uint32_t max_samples)
{
    follow_scene_updates();
    const std::uint32_t pixels =
        m_pixels_listed ? static_cast<std::uint32_t>(m_pixel_list.size()) : m_params.width * m_params.height;
    std::uint32_t samples = 1;
    if (m_integrator->plans_passes_by_time()) {
        samples = m_planner.next(max_samples);
    } else {
        samples = std::min(max_samples, m_integrator->max_samples_per_pass(pixels));
        if (m_settings.samples_per_pass != 0) samples = std::min(samples, m_settings.samples_per_pass);
        samples = std::max(samples, 1u);
    }
    const auto start = std::chrono::steady_clock::now();
    m_params.sample_index = m_next_sample;
    m_params.samples_in_pass = samples;
    m_params.pixels_per_item = 1;
    m_params.flags &= ~GC_RENDER_PIXEL_LIST;
    if (m_pixels_listed) m_params.flags |= GC_RENDER_PIXEL_LIST;
    m_integrator->begin_pass(m_params);
    for (std::uint32_t offset = 0; offset < pixels; offset += m_batch_pixels) {
        m_params.pixel_offset = offset;
        m_params.pixel_count = std::min(m_batch_pixels, pixels - offset);
        m_integrator->render_batch(m_params, *m_scene, m_film);
    }
    m_context.finish();
    m_integrator->end_pass();
    m_planner.record(samples, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    m_sample_count += samples;
    m_next_sample += samples;
    return samples;
}

double Renderer::estimate_seconds_per_sample(std::uint32_t probe_pixels)
{
    std::vector<std::uint32_t> selected = m_pixel_list;
    const bool listed = m_pixels_listed;
    const std::uint32_t pixels = listed ? static_cast<std::uint32_t>(selected.size()) : m_params.width * m_params.height;
    if (pixels == 0) return 0.0;
    // Runs of neighbouring pixels (a megakernel's camera packets take neighbours; isolated
    // pixels would make them incoherent and the estimate slow), one in each of `runs` equal
    // stretches of the pixels, placed along its stretch by the golden-ratio sequence so that
    // the runs do not line up in a few columns of the image.
    constexpr std::uint32_t kRun = 32;
    const std::uint32_t runs = std::clamp(probe_pixels / kRun, 1u, std::max(1u, pixels / kRun));
    std::vector<std::uint32_t> probe;
    for (std::uint32_t r = 0; r < runs; ++r) {
        const std::uint64_t begin = std::uint64_t(pixels) * r / runs;
        const std::uint64_t end = std::uint64_t(pixels) * (r + 1) / runs;
        const std::uint64_t slack = end - begin > kRun ? end - begin - kRun : 0;
        const double along = 0.6180339887498949 * r;
        const std::uint64_t start = begin + static_cast<std::uint64_t>((along - std::floor(along)) * double(slack));
        for (std::uint64_t i = start; i < std::min<std::uint64_t>(start + kRun, end); ++i)
            probe.push_back(listed ? selected[i] : static_cast<std::uint32_t>(i));
    }
    const std::uint32_t next = m_next_sample;
    const PassPlanner plan = m_planner;
    select_pixels(probe);
    m_planner = PassPlanner(1);
    render_samples(1);
    m_planner = PassPlanner(kProbeSamples);
    render_samples(kProbeSamples);
    const double probe_seconds_per_sample = m_planner.seconds_per_sample();  // the pass just timed
    m_planner = plan;
    m_next_sample = next;
    if (listed)
        select_pixels(std::move(selected));
    else
        select_all_pixels();
    return probe_seconds_per_sample * (static_cast<double>(pixels) / static_cast<double>(probe.size()));
}

FilmSums Renderer::sums(bool with_squares) const
{
    FilmSums out;
    out.width = m_params.width;
    out.height = m_params.height;
    out.sums.resize(m_film.sums.count());
    m_film.sums.read(out.sums);
    if (with_squares) {
        out.squares.resize(m_film.squares.count());
        m_film.squares.read(out.squares);
    }
    out.sample_counts = pixel_sample_counts();
    return out;
}

cl_event Renderer::copy_sums(const cl::Buffer<glm::vec4>& sums, const cl::Buffer<glm::vec4>* squares,
                             FilmSums& header) const
{
    header = FilmSums{};
    header.width = m_params.width;
    header.height = m_params.height;
    header.sample_counts = pixel_sample_counts();
    const auto check = [](const cl::Buffer<glm::vec4>& from, const cl::Buffer<glm::vec4>& to) {
        if (to.count() != from.count())
            throw UsageError("a copy of the film needs a buffer of " + std::to_string(from.count()) + " pixels, not " +
                             std::to_string(to.count()));
    };
    check(m_film.sums, sums);
    if (squares) check(m_film.squares, *squares);
    // The queue is in order: the last copy's event marks both done.
    cl_event done = nullptr;
    GC_CL_WHAT("copying the film", clEnqueueCopyBuffer, m_context.queue(), m_film.sums.mem(), sums.mem(), 0, 0,
               m_film.sums.bytes(), 0, nullptr, squares ? nullptr : &done);
    if (squares)
        GC_CL_WHAT("copying the film's squares", clEnqueueCopyBuffer, m_context.queue(), m_film.squares.mem(),
                   squares->mem(), 0, 0, m_film.squares.bytes(), 0, nullptr, &done);
    return done;
}

std::vector<std::uint32_t> Renderer::pixel_sample_counts() const
{
    const std::size_t pixels = std::size_t(m_params.width) * m_params.height;
    if (!m_pixels_listed) return std::vector<std::uint32_t>(pixels, m_sample_count);
    std::vector<std::uint32_t> counts(pixels, 0u);
    for (std::uint32_t p : m_pixel_list) counts[p] = m_sample_count;
    return counts;
}

Film Renderer::film() const
{
    const std::size_t pixels = m_film.sums.count();
    std::vector<glm::vec4> sums(pixels);
    m_film.sums.read(sums);
    const std::vector<std::uint32_t> counts = pixel_sample_counts();
    Film film(m_params.width, m_params.height);
    for (std::size_t i = 0; i < pixels; ++i) {
        const float inv = counts[i] > 0 ? 1.0f / static_cast<float>(counts[i]) : 0.0f;
        const std::uint32_t x = static_cast<std::uint32_t>(i % m_params.width);
        const std::uint32_t y = static_cast<std::uint32_t>(i / m_params.width);
        film.set(x, y, Rgba{sums[i].x * inv, sums[i].y * inv, sums[i].z * inv, 1.0f});
    }
    return film;
}

Film Renderer::variance() const { return sample_variance(sums()); }

}  // namespace gc
