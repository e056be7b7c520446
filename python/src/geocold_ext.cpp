// geocold._geocold: the nanobind module under the `geocold` Python package (python/geocold).
// It binds the library's front door (host/render/session.h, renderer.h, render_loop.h) and
// leaves the Pythonic surface (Material, Camera, params, docstrings) to the pure-Python layer.
//
// Threads and signals: every call that waits for a device releases the GIL; the render loop
// takes it back after each pass to run the progress callback and PyErr_CheckSignals, so Ctrl-C
// raises KeyboardInterrupt at the next pass boundary with the film intact.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/function.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "host/app/cli.h"
#include "host/app/environment.h"
#include "host/cl/device.h"
#include "host/image/image_io.h"
#include "host/image/image_module.h"
#include "host/render/adaptive.h"
#include "host/render/chunks.h"
#include "host/render/device_scene.h"
#include "host/render/environment.h"
#include "host/render/gradients.h"
#include "host/render/multi_device.h"
#include "host/render/render_loop.h"
#include "host/render/renderer.h"
#include "host/render/scene_params.h"
#include "host/render/session.h"
#include "host/scene/camera_framing.h"
#include "host/util/error.h"

namespace nb = nanobind;
using namespace nb::literals;

namespace gc::python {
namespace {

using Clock = std::chrono::steady_clock;
using Vec3Tuple = std::tuple<float, float, float>;
using FloatArray = nb::ndarray<nb::numpy, float>;
using UintArray = nb::ndarray<nb::numpy, std::uint32_t>;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Where the package keeps its kernels (set by geocold/__init__.py): the default when
// GEOCOLD_KERNEL_DIR is not set.
std::filesystem::path g_package_kernel_dir;

RenderSetup python_render_setup()
{
    RenderSetup setup = render_setup_from_environment();
    if (setup.build.kernel_dir.empty()) setup.build.kernel_dir = g_package_kernel_dir;
    return setup;
}

// An array that owns a moved-in std::vector: no copy of the film.
template <class T, class Element>
nb::ndarray<nb::numpy, Element> array_from(std::vector<T>&& values, std::initializer_list<size_t> shape)
{
    auto* owned = new std::vector<T>(std::move(values));
    nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
    return nb::ndarray<nb::numpy, Element>(reinterpret_cast<Element*>(owned->data()), shape, owner);
}

FloatArray film_array(Film&& film)
{
    const size_t h = film.height(), w = film.width();
    return array_from<float, float>(std::move(film.data()), {h, w, 4});
}

void check_finite(const char* what, float v)
{
    if (!std::isfinite(v)) throw UsageError(std::string(what) + " must be finite, not " + std::to_string(v));
}

glm::vec3 colour(const char* what, const Vec3Tuple& t, bool bounded)
{
    const glm::vec3 c(std::get<0>(t), std::get<1>(t), std::get<2>(t));
    for (int i = 0; i < 3; ++i) {
        check_finite(what, c[i]);
        if (c[i] < 0.0f || (bounded && c[i] > 1.0f))
            throw UsageError(std::string(what) + " components must lie in " + (bounded ? "[0, 1]" : "[0, inf)") +
                             ", not " + std::to_string(c[i]));
    }
    return c;
}

Vec3Tuple tuple_of(const glm::vec3& v) { return {v.x, v.y, v.z}; }

const char* type_name(MaterialType t)
{
    switch (t) {
    case MaterialType::Lambert: return "lambert";
    case MaterialType::Phong: return "phong";
    case MaterialType::Mirror: return "mirror";
    case MaterialType::Dielectric: return "dielectric";
    case MaterialType::Pbr: return "pbr";
    }
    return "?";
}

// A loaded scene: what gc.load returns, shared by every renderer made from it. Edits of the
// materials and the camera bump a revision; renderers follow it at their next render.
struct SceneState {
    PreparedScene prepared;
    std::string path;
    std::atomic<std::uint64_t> material_revision{0};
    std::atomic<std::uint64_t> camera_revision{0};
    std::atomic<std::uint64_t> texture_revision{0};  // texels set (textures/<i>/texels)
    double load_seconds = 0.0;
    double bvh_seconds = 0.0;
    std::mutex mutex;  // guards the host scene against renderers uploading it on other threads

    Material& material(std::size_t i)
    {
        if (i >= prepared.scene.materials.size()) throw nb::index_error("no such material");
        return prepared.scene.materials[i];
    }
};

// The differentiable parameters (scene_params.h): (name, shape) in the library's order.
std::vector<std::tuple<std::string, std::vector<std::size_t>>> param_shapes(SceneState& s)
{
    const std::lock_guard<std::mutex> lock(s.mutex);
    std::vector<std::tuple<std::string, std::vector<std::size_t>>> out;
    for (const ParamInfo& p : list_params(s.prepared.scene)) out.emplace_back(p.name, p.shape);
    return out;
}

Texture& differentiable_texture(SceneState& s, std::uint32_t index)
{
    // resolve_param says why a texture is not a parameter (out of range, or a normal map).
    resolve_param(s.prepared.scene, "textures/" + std::to_string(index) + "/texels");
    return s.prepared.scene.textures[index];
}

FloatArray get_texels(SceneState& s, std::uint32_t index)
{
    const std::lock_guard<std::mutex> lock(s.mutex);
    const Texture& t = differentiable_texture(s, index);
    return array_from<float, float>(texels_linear(t), {size_t(t.height), size_t(t.width), 4});
}

// Stores the texture as linear floats from now on (Texture::linear); renderers upload it at
// their next render.
void set_texels(SceneState& s, std::uint32_t index, nb::ndarray<const float, nb::c_contig, nb::device::cpu> texels)
{
    const std::lock_guard<std::mutex> lock(s.mutex);
    Texture& t = differentiable_texture(s, index);
    if (texels.ndim() != 3 || texels.shape(0) != t.height || texels.shape(1) != t.width || texels.shape(2) != 4)
        throw UsageError("textures/" + std::to_string(index) + "/texels must be (" + std::to_string(t.height) + ", " +
                         std::to_string(t.width) + ", 4) float32");
    const float* v = texels.data();
    const std::size_t count = std::size_t(t.width) * t.height;
    const std::string what = "textures/" + std::to_string(index) + "/texels";
    for (std::size_t i = 0; i < 4 * count; ++i) check_finite(what.c_str(), v[i]);
    t.linear.resize(count);
    for (std::size_t i = 0; i < count; ++i) t.linear[i] = glm::vec4(v[4 * i], v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]);
    ++s.texture_revision;
}

std::shared_ptr<SceneState> load(const std::string& path, int gltf_scene, bool phong_as_lambert)
{
    auto state = std::make_shared<SceneState>();
    state->path = path;
    SceneRequest request;
    request.path = path;
    request.load.gltf_scene = gltf_scene;
    request.load.phong_as_lambert = phong_as_lambert;
    {
        nb::gil_scoped_release release;
        auto start = Clock::now();
        state->prepared = load_with_camera(request);
        state->load_seconds = seconds_since(start);
        start = Clock::now();
        state->prepared.bvh = build_bvh(state->prepared.scene);
        state->bvh_seconds = seconds_since(start);
    }
    return state;
}

nb::dict material_fields(const Material& m)
{
    nb::dict d;
    d["name"] = m.name;
    d["type"] = type_name(m.type);
    d["base_color"] = tuple_of(m.albedo);
    d["specular"] = tuple_of(m.specular);
    d["emission"] = tuple_of(m.emission);
    d["phong_exponent"] = m.phong_exponent;
    d["ior"] = m.ior;
    d["opacity"] = m.opacity;
    d["metallic"] = m.metallic;
    d["roughness"] = m.roughness;
    d["transmission"] = m.transmission;
    d["normal_scale"] = m.normal_scale;
    d["alpha_cutoff"] = m.alpha_cutoff;
    d["double_sided"] = m.double_sided;
    return d;
}

void set_material_field(SceneState& s, std::size_t index, const std::string& field, nb::handle value)
{
    const std::lock_guard<std::mutex> lock(s.mutex);
    Material& m = s.material(index);
    const std::string what = "materials/" + m.name + "/" + field;
    const auto unit = [&](float& out) {
        const float v = nb::cast<float>(value);
        check_finite(what.c_str(), v);
        if (v < 0.0f || v > 1.0f) throw UsageError(what + " must lie in [0, 1], not " + std::to_string(v));
        out = v;
    };
    if (field == "base_color") m.albedo = colour(what.c_str(), nb::cast<Vec3Tuple>(value), true);
    else if (field == "specular") m.specular = colour(what.c_str(), nb::cast<Vec3Tuple>(value), true);
    else if (field == "emission") m.emission = colour(what.c_str(), nb::cast<Vec3Tuple>(value), false);
    else if (field == "roughness") unit(m.roughness);
    else if (field == "metallic") unit(m.metallic);
    else if (field == "opacity") unit(m.opacity);
    else if (field == "transmission") unit(m.transmission);
    else if (field == "alpha_cutoff") unit(m.alpha_cutoff);
    else if (field == "ior" || field == "phong_exponent" || field == "normal_scale") {
        const float v = nb::cast<float>(value);
        check_finite(what.c_str(), v);
        if (field == "ior") {
            if (v <= 0.0f) throw UsageError(what + " must be positive, not " + std::to_string(v));
            m.ior = v;
        } else if (field == "phong_exponent") {
            if (v < 0.0f) throw UsageError(what + " must not be negative, not " + std::to_string(v));
            m.phong_exponent = v;
        } else {
            m.normal_scale = v;
        }
    } else if (field == "double_sided") {
        m.double_sided = nb::cast<bool>(value);
    } else if (field == "type") {
        const std::string t = nb::cast<std::string>(value);
        if (t == "lambert") m.type = MaterialType::Lambert;
        else if (t == "phong") m.type = MaterialType::Phong;
        else if (t == "mirror") m.type = MaterialType::Mirror;
        else if (t == "dielectric") m.type = MaterialType::Dielectric;
        else if (t == "pbr") m.type = MaterialType::Pbr;
        else throw UsageError(what + " must be one of lambert, phong, mirror, dielectric, pbr, not '" + t + "'");
    } else {
        throw UsageError("materials/" + m.name + " has no editable field '" + field + "'");
    }
    ++s.material_revision;
}

nb::dict camera_fields(const Camera& c)
{
    nb::dict d;
    d["look_from"] = Vec3Tuple{c.look_from.x, c.look_from.y, c.look_from.z};
    d["look_at"] = Vec3Tuple{c.look_at.x, c.look_at.y, c.look_at.z};
    d["up"] = Vec3Tuple{c.up.x, c.up.y, c.up.z};
    d["fov"] = c.vfov_degrees;
    d["aperture"] = c.aperture_radius;
    d["focus_distance"] = c.focus_distance;
    return d;
}

void set_camera(SceneState& s, const Vec3Tuple& from, const Vec3Tuple& at, const Vec3Tuple& up, float fov,
                float aperture, float focus_distance)
{
    const std::lock_guard<std::mutex> lock(s.mutex);
    CameraOverrides o;
    o.look_from = Point3(std::get<0>(from), std::get<1>(from), std::get<2>(from));
    o.look_at = Point3(std::get<0>(at), std::get<1>(at), std::get<2>(at));
    o.up = Vec3(std::get<0>(up), std::get<1>(up), std::get<2>(up));
    o.fov = fov;
    o.aperture_radius = aperture;
    o.focus_distance = focus_distance;
    for (float v : {std::get<0>(from), std::get<1>(from), std::get<2>(from), std::get<0>(at), std::get<1>(at),
                    std::get<2>(at), std::get<0>(up), std::get<1>(up), std::get<2>(up), fov, aperture, focus_distance})
        check_finite("camera", v);
    // The same checks as the CLI's --look-from/--look-at/--up/--fov/--aperture/--focus-distance
    // (UsageError).
    s.prepared.camera = resolve_camera(s.prepared.scene, o);
    ++s.camera_revision;
}

IntegratorKind parse_integrator(const std::string& text)
{
    if (const auto kind = integrator_from_name(text)) return *kind;
    throw UsageError("integrator must be one of path, whitted, aov, not '" + text + "'");
}

AovKind parse_aov(const std::string& text)
{
    if (const auto kind = aov_from_name(text)) return *kind;
    throw UsageError("aov must be one of preview, albedo, normal, depth, primid, guide-albedo, guide-normal, not '" + text + "'");
}

SamplerKind parse_sampler(const std::string& text)
{
    if (const auto kind = sampler_from_name(text)) return *kind;
    throw UsageError("sampler must be one of independent, sobol, not '" + text + "'");
}

// The settings both gc.Renderer and gc.render_frame take, checked as the CLI checks them.
RenderSettings render_settings(const std::string& integrator, const std::string& aov, int width, int height,
                               std::uint32_t spp, std::uint32_t seed, const std::string& sampler,
                               std::uint32_t max_depth, std::uint32_t rr_depth, const Vec3Tuple& env,
                               const std::string& env_map)
{
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        throw UsageError("res must be two sizes in [1, 65536], not (" + std::to_string(width) + ", " +
                         std::to_string(height) + ")");
    if (max_depth < 1) throw UsageError("max_depth must be at least 1");
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.integrator = parse_integrator(integrator);
    settings.aov = parse_aov(aov);
    settings.spp = spp;
    settings.seed = seed;
    settings.sampler = parse_sampler(sampler);
    settings.max_depth = max_depth;
    settings.rr_depth = rr_depth;
    settings.env_radiance = colour("env", env, false);
    settings.env_map_path = env_map;
    return settings;
}

// One frame on several devices at once (host/render/multi_device.h): chunks of chunk_samples
// samples, added in chunk order, so devices of one kind give the bits of one. Returns the mean
// of samples [first, end) (or of the prefix a time limit left) and its sample count (with a
// noise threshold > 0, adaptive sampling, host/render/adaptive.h: the cap, each pixel's mean
// over its own samples). The
// frame runs on its own thread while this one, holding the GIL now and then, watches for
// Ctrl-C (Python sees signals only on the main thread).
std::tuple<FloatArray, std::uint32_t> render_frame_on(std::shared_ptr<SceneState> state,
                                                      const std::vector<std::string>& device_specs,
                                                      const std::string& integrator, const std::string& aov, int width,
                                                      int height, std::uint32_t first, std::uint32_t end,
                                                      std::uint32_t chunk_samples, std::uint32_t seed,
                                                      const std::string& sampler, std::uint32_t max_depth, std::uint32_t rr_depth,
                                                      const Vec3Tuple& env, const std::string& env_map, double time_limit,
                                                      double noise_threshold)
{
    if (time_limit < 0.0 || !std::isfinite(time_limit))
        throw UsageError("time_limit must be a non-negative number of seconds");
    if (noise_threshold < 0.0 || !std::isfinite(noise_threshold))
        throw UsageError("noise_threshold must be a relative standard error > 0, or 0 for none");
    if (device_specs.empty()) throw UsageError("devices must name at least one device");
    RenderSettings settings =
        render_settings(integrator, aov, width, height, end, seed, sampler, max_depth, rr_depth, env, env_map);
    const ChunkPlan plan = ChunkPlan::for_range(first, end, chunk_samples);
    FrameRounds rounds;
    if (noise_threshold > 0.0) {
        if (settings.integrator != IntegratorKind::Path)
            throw UsageError("noise_threshold needs integrator='path', not '" + integrator + "'");
        if (first != 0)
            throw UsageError("noise_threshold cannot render a sample range (samples=...): its decisions need every "
                             "earlier sample of the frame");
        settings.noise_threshold = noise_threshold;
        rounds = adaptive_rounds(noise_threshold, end, chunk_samples);
    }
    const RenderSetup setup = python_render_setup();

    std::vector<cl::DeviceInfo> devices;
    {
        nb::gil_scoped_release release;
        if (device_specs.size() == 1 && device_specs[0] == "all") {
            std::string why;
            devices = cl::list_devices(&why);
            if (devices.empty()) throw DeviceError("no OpenCL device found: " + why);
        } else {
            for (const std::string& spec : device_specs) devices.push_back(cl::select_device(spec));
        }
    }
    std::atomic<bool> stop{false};
    std::atomic<bool> done{false};
    FrameResult result;
    std::exception_ptr error;
    FrameControl control;
    control.time_limit_seconds = time_limit;
    control.cancelled = [&] { return stop.load(); };
    bool interrupted = false;
    {
        std::thread frame([&] {
            try {
                const std::lock_guard<std::mutex> lock(state->mutex);
                result = render_frame(devices, state->prepared, settings, setup, plan, control, rounds);
            } catch (...) {
                error = std::current_exception();
            }
            done = true;
        });
        while (!done) {
            {
                nb::gil_scoped_release release;
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
            if (!interrupted && PyErr_CheckSignals() != 0) {
                interrupted = true;
                stop = true;
            }
        }
        frame.join();
    }
    if (interrupted) throw nb::python_error();  // the KeyboardInterrupt PyErr_CheckSignals raised
    if (error) std::rethrow_exception(error);
    if (result.sums.width == 0) {
        result.sums.width = std::uint32_t(width);
        result.sums.height = std::uint32_t(height);
        result.sums.sums.assign(std::size_t(width) * height, glm::vec4(0.0f));
    }
    Film mean = mean_film(result.sums);
    return {film_array(std::move(mean)), result.end_sample - first};
}

// gc.Renderer: a context on one device, the scene uploaded to it, a Renderer over it.
class PyRenderer {
public:
    PyRenderer(std::shared_ptr<SceneState> scene, const std::string& device, const std::string& integrator,
               const std::string& aov, int width, int height, std::uint32_t spp, std::uint32_t seed,
               const std::string& sampler,
               std::uint32_t max_depth, std::uint32_t rr_depth, const Vec3Tuple& env, const std::string& env_map,
               std::uint32_t samples_per_pass, std::uint32_t wavefront_size)
        : m_state(std::move(scene)),
          m_settings(render_settings(integrator, aov, width, height, spp, seed, sampler, max_depth, rr_depth, env,
                                     env_map))
    {
        m_settings.samples_per_pass = samples_per_pass;
        m_settings.wavefront_size = wavefront_size;
        const RenderSetup setup = python_render_setup();

        nb::gil_scoped_release release;
        const cl::DeviceInfo info = cl::select_device(device);
        const std::lock_guard<std::mutex> lock(m_state->mutex);
        auto start = Clock::now();
        m_context = std::make_unique<cl::Context>(info);
        m_scene = std::make_shared<DeviceScene>(DeviceScene::upload(*m_context, m_state->prepared.scene,
                                                                    m_state->prepared.bvh,
                                                                    load_environment_map(m_settings), setup.tuning));
        m_upload_seconds = seconds_since(start);
        m_renderer = std::make_unique<Renderer>(*m_context, m_scene, m_state->prepared.camera, m_settings, setup);
        m_material_revision = m_state->material_revision;
        m_camera_revision = m_state->camera_revision;
        m_program = &m_renderer->program();
    }

    // Adds `spp` samples (continuing the film) unless `time_limit` (seconds, 0: none) or
    // Ctrl-C stops it first. Returns the mean film.
    FloatArray render(std::optional<std::uint32_t> spp, double time_limit,
                      std::optional<std::function<void(std::uint32_t, std::uint32_t)>> progress)
    {
        if (time_limit < 0.0 || !std::isfinite(time_limit))
            throw UsageError("time_limit must be a non-negative number of seconds");
        const std::uint32_t wanted = spp.value_or(m_settings.spp);
        bool interrupted = false;
        std::exception_ptr callback_error;
        std::uint32_t target = 0;
        {
            nb::gil_scoped_release release;
            follow_edits();
            const std::uint32_t done = m_renderer->samples_done();
            target = done + wanted;
            RenderControl control;
            control.time_limit_seconds = time_limit;
            control.on_pass = [&](std::uint32_t samples) {
                if (!progress || !*progress) return;
                nb::gil_scoped_acquire acquire;
                try {
                    (*progress)(samples, target);
                } catch (...) {
                    callback_error = std::current_exception();
                }
            };
            control.cancelled = [&] {
                if (callback_error) return true;
                nb::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) interrupted = true;
                return interrupted;
            };
            const RenderOutcome outcome = render_to(*m_renderer, target, control);
            m_seconds += outcome.seconds;
            if (&m_renderer->program() != m_program) {
                ++m_program_builds;
                m_program = &m_renderer->program();
            }
        }
        if (callback_error) std::rethrow_exception(callback_error);
        if (interrupted) throw nb::python_error();  // the KeyboardInterrupt PyErr_CheckSignals raised
        return film();
    }

    FloatArray film() const
    {
        Film f;
        {
            nb::gil_scoped_release release;
            f = m_renderer->film();
        }
        return film_array(std::move(f));
    }

    FloatArray variance() const
    {
        Film f;
        {
            nb::gil_scoped_release release;
            f = m_renderer->variance();
        }
        return film_array(std::move(f));
    }

    std::tuple<FloatArray, FloatArray, UintArray> sums() const
    {
        FilmSums s;
        {
            nb::gil_scoped_release release;
            s = m_renderer->sums();
        }
        const size_t h = s.height, w = s.width;
        return {array_from<glm::vec4, float>(std::move(s.sums), {h, w, 4}),
                array_from<glm::vec4, float>(std::move(s.squares), {h, w, 4}),
                array_from<std::uint32_t, std::uint32_t>(std::move(s.sample_counts), {h, w})};
    }

    void clear() { m_renderer->clear(); }

    // d loss / d parameter (gradients.h) for a loss of this renderer's image, given d loss / d
    // each pixel's mean as an (H, W, 3 or 4) array; flat float32 arrays by name.
    nb::dict backward(nb::ndarray<const float, nb::c_contig, nb::device::cpu> loss_grad,
                      const std::vector<std::string>& params, std::uint32_t spp, std::uint32_t seed)
    {
        const std::size_t w = m_settings.width, h = m_settings.height;
        if (loss_grad.ndim() != 3 || loss_grad.shape(0) != h || loss_grad.shape(1) != w ||
            (loss_grad.shape(2) != 3 && loss_grad.shape(2) != 4))
            throw UsageError("backward: loss_grad must be (" + std::to_string(h) + ", " + std::to_string(w) +
                             ", 3 or 4) float32, the image's shape");
        if (spp == 0) throw UsageError("backward: spp must be at least 1");
        const std::size_t channels = loss_grad.shape(2);
        std::vector<glm::vec4> grad(w * h);
        const float* g = loss_grad.data();
        for (std::size_t i = 0; i < grad.size(); ++i) {
            grad[i] = glm::vec4(g[i * channels], g[i * channels + 1], g[i * channels + 2], 0.0f);
            for (int c = 0; c < 3; ++c) check_finite("backward: loss_grad", grad[i][c]);
        }
        Gradients result;
        {
            nb::gil_scoped_release release;
            follow_edits();
            if (!m_adjoint) m_adjoint = std::make_unique<PathAdjoint>(*m_renderer);
            const std::lock_guard<std::mutex> lock(m_state->mutex);
            result = m_adjoint->backward(*m_renderer, m_state->prepared.scene, grad, params, spp, seed);
        }
        nb::dict out;
        for (auto& [name, values] : result) {
            const size_t n = values.size();
            out[nb::str(name.c_str())] = array_from<float, float>(std::move(values), {n});
        }
        return out;
    }

    // 0 after a scene edit not yet rendered: the next render restarts the film.
    std::uint32_t sample_count() const
    {
        if (m_state->material_revision != m_material_revision || m_state->camera_revision != m_camera_revision ||
            m_state->texture_revision != m_texture_revision)
            return 0;
        return m_renderer->samples_done();
    }

    nb::dict info() const
    {
        nb::dict d;
        const cl::DeviceInfo& dev = m_context->device();
        d["device"] = dev.device_name + " (" + dev.platform_name + ")";
        d["integrator"] = integrator_name(m_settings.integrator);
        d["aov"] = aov_name(m_settings.aov);
        d["width"] = m_settings.width;
        d["height"] = m_settings.height;
        d["seed"] = m_settings.seed;
        d["sampler"] = sampler_name(m_settings.sampler);
        d["load_seconds"] = m_state->load_seconds;
        d["bvh_seconds"] = m_state->bvh_seconds;
        d["upload_seconds"] = m_upload_seconds;
        d["compile_seconds"] = m_renderer->program().build_seconds();
        d["program_from_cache"] = m_renderer->program().from_cache();
        d["program_builds"] = m_program_builds;
        d["render_seconds"] = m_seconds;
        return d;
    }

private:
    // Brings the device up to date with the scene's edits: materials through
    // DeviceScene::update_materials (no geometry upload; a program only if the kernel features
    // changed), the camera through set_camera. Either restarts the film.
    void follow_edits()
    {
        // Called without the GIL: the setters hold the GIL while they take the mutex.
        const std::lock_guard<std::mutex> lock(m_state->mutex);
        if (m_state->texture_revision != m_texture_revision) {
            m_scene->update_textures(*m_context, m_state->prepared.scene);  // the materials too
            m_texture_revision = m_state->texture_revision;
            m_material_revision = m_state->material_revision;
        }
        if (m_state->material_revision != m_material_revision) {
            m_scene->update_materials(*m_context, m_state->prepared.scene);
            m_material_revision = m_state->material_revision;
        }
        if (m_state->camera_revision != m_camera_revision) {
            m_renderer->set_camera(m_state->prepared.camera);
            m_camera_revision = m_state->camera_revision;
        }
    }

    std::shared_ptr<SceneState> m_state;
    RenderSettings m_settings;
    // Declared in this order so that the renderer goes first, then the scene, then the context.
    std::unique_ptr<cl::Context> m_context;
    std::shared_ptr<DeviceScene> m_scene;
    std::unique_ptr<Renderer> m_renderer;
    const cl::Program* m_program = nullptr;
    std::uint64_t m_material_revision = 0;
    std::uint64_t m_camera_revision = 0;
    std::uint64_t m_texture_revision = 0;
    std::unique_ptr<PathAdjoint> m_adjoint;  // built at the first backward
    std::uint32_t m_program_builds = 0;  // programs built after the first (kernel feature changes)
    double m_upload_seconds = 0.0;
    double m_seconds = 0.0;
};

std::vector<nb::dict> devices()
{
    std::string why;
    std::vector<cl::DeviceInfo> list;
    {
        nb::gil_scoped_release release;
        list = cl::list_devices(&why);
    }
    std::vector<nb::dict> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const cl::DeviceInfo& d = list[i];
        nb::dict e;
        e["index"] = i;
        e["kind"] = d.type_name();
        e["name"] = d.device_name;
        e["platform"] = d.platform_name;
        e["vendor"] = d.vendor;
        e["driver"] = d.driver_version;
        e["compute_units"] = d.compute_units;
        e["global_memory"] = d.global_mem;
        out.push_back(std::move(e));
    }
    return out;
}

void write_file(const std::string& path, nb::ndarray<float, nb::ndim<3>, nb::c_contig, nb::device::cpu> image,
           const std::string& device, const std::string& integrator, const std::string& scene, std::uint32_t spp,
           double seconds, std::uint32_t seed, const std::string& tonemap, float exposure)
{
    const std::optional<Tonemap> curve = parse_tonemap(tonemap);
    if (!curve) throw UsageError("write: tonemap must be one of " + std::string(tonemap_names()) + ", not '" + tonemap + "'");
    if (!std::isfinite(exposure)) throw UsageError("write: exposure must be a finite number of stops");
    const size_t h = image.shape(0), w = image.shape(1), c = image.shape(2);
    if (c != 3 && c != 4) throw UsageError("write: the image must be (height, width, 3 or 4), not " + std::to_string(c) + " channels");
    if (h == 0 || w == 0) throw UsageError("write: the image is empty");
    Film film(static_cast<uint32_t>(w), static_cast<uint32_t>(h));
    const float* src = image.data();
    std::vector<float>& dst = film.data();
    for (size_t i = 0; i < h * w; ++i)
        for (size_t k = 0; k < 4; ++k) dst[4 * i + k] = k < c ? src[c * i + k] : 1.0f;
    ImageMetadata meta{device, integrator, scene, spp, seconds, seed};
    nb::gil_scoped_release release;
    check_output_path(path);
    write_image(path, film, meta, DisplayTransform{*curve, exposure});
}

FloatArray read_file(const std::string& path)
{
    Film film;
    {
        nb::gil_scoped_release release;
        film = read_image(path);
    }
    return film_array(std::move(film));
}

int cli_main(const std::vector<std::string>& args)
{
    nb::gil_scoped_release release;
    return run_cli(args);
}

}  // namespace
}  // namespace gc::python

NB_MODULE(_geocold, m)
{
    using namespace gc::python;
    m.doc() = "The compiled core of geocold; use the `geocold` package.";

    // gc.Error and its subclasses; a bad argument (the CLI's usage errors) is also a ValueError.
    static nb::object error = nb::steal(PyErr_NewExceptionWithDoc(
        "geocold.Error", "Base class of every error geocold raises.", PyExc_RuntimeError, nullptr));
    static nb::object scene_error = nb::steal(PyErr_NewExceptionWithDoc(
        "geocold.SceneError", "A scene, texture or image file that cannot be read or makes no sense.", error.ptr(),
        nullptr));
    static nb::object device_error = nb::steal(PyErr_NewExceptionWithDoc(
        "geocold.DeviceError", "No usable device, or an OpenCL failure.", error.ptr(), nullptr));
    static nb::object output_error = nb::steal(PyErr_NewExceptionWithDoc(
        "geocold.OutputError", "An output image that could not be written.", error.ptr(), nullptr));
    nb::object bases = nb::make_tuple(error, nb::handle(PyExc_ValueError));
    static nb::object argument_error = nb::steal(PyErr_NewExceptionWithDoc(
        "geocold.ArgumentError", "A bad argument: a geocold.Error that is also a ValueError.", bases.ptr(),
        nullptr));
    m.attr("Error") = error;
    m.attr("SceneError") = scene_error;
    m.attr("DeviceError") = device_error;
    m.attr("OutputError") = output_error;
    m.attr("ArgumentError") = argument_error;
    nb::register_exception_translator([](const std::exception_ptr& p, void*) {
        try {
            std::rethrow_exception(p);
        } catch (const gc::InputError& e) {
            PyErr_SetString(scene_error.ptr(), e.what());
        } catch (const gc::DeviceError& e) {
            PyErr_SetString(device_error.ptr(), e.what());
        } catch (const gc::OutputError& e) {
            PyErr_SetString(output_error.ptr(), e.what());
        } catch (const gc::UsageError& e) {
            PyErr_SetString(argument_error.ptr(), e.what());
        } catch (const gc::Error& e) {
            PyErr_SetString(error.ptr(), e.what());
        }
    });

    m.def("_configure", [](const std::string& kernel_dir, const std::string& image_module) {
        g_package_kernel_dir = kernel_dir;
#ifdef GC_HAVE_OIIO
        if (!image_module.empty()) gc::set_image_module_path(image_module);
#else
        (void)image_module;  // no module: the built-in formats only
#endif
    });
    m.def("devices", &devices);
    m.def("load", &load, "path"_a, "gltf_scene"_a = -1, "phong_as_lambert"_a = false);
    m.def("write", &write_file, "path"_a, "image"_a, "device"_a, "integrator"_a, "scene"_a, "spp"_a, "seconds"_a, "seed"_a,
          "tonemap"_a = "pbr-neutral", "exposure"_a = 0.0f);
    m.def("read", &read_file, "path"_a);
    m.def("cli_main", &cli_main, "args"_a);
    m.def("render_frame", &render_frame_on, "scene"_a, "devices"_a, "integrator"_a, "aov"_a, "width"_a, "height"_a,
          "first"_a, "end"_a, "chunk_samples"_a, "seed"_a, "sampler"_a, "max_depth"_a, "rr_depth"_a, "env"_a, "env_map"_a,
          "time_limit"_a, "noise_threshold"_a);
    m.def("has_oiio", [] { return gc::image_io_has_oiio(); });

    nb::class_<SceneState>(m, "SceneState")
        .def_ro("path", &SceneState::path)
        .def_ro("load_seconds", &SceneState::load_seconds)
        .def_ro("bvh_seconds", &SceneState::bvh_seconds)
        .def("triangle_count", [](const SceneState& s) { return s.prepared.scene.triangle_count(); })
        .def("material_count", [](const SceneState& s) { return s.prepared.scene.materials.size(); })
        .def("material", [](SceneState& s, std::size_t i) { return material_fields(s.material(i)); })
        .def("set_material", &set_material_field)
        .def("camera", [](const SceneState& s) { return camera_fields(s.prepared.camera); })
        .def("set_camera", &set_camera)
        .def("param_shapes", &param_shapes)
        .def("texels", &get_texels)
        .def("set_texels", &set_texels);

    nb::class_<PyRenderer>(m, "RendererCore")
        .def(nb::init<std::shared_ptr<SceneState>, const std::string&, const std::string&, const std::string&, int, int,
                      std::uint32_t, std::uint32_t, const std::string&, std::uint32_t, std::uint32_t, const Vec3Tuple&, const std::string&,
                      std::uint32_t, std::uint32_t>())
        .def("render", &PyRenderer::render, "spp"_a.none(), "time_limit"_a, "progress"_a.none())
        .def("film", &PyRenderer::film)
        .def("variance", &PyRenderer::variance)
        .def("sums", &PyRenderer::sums)
        .def("clear", &PyRenderer::clear)
        .def("backward", &PyRenderer::backward, "loss_grad"_a, "params"_a, "spp"_a, "seed"_a)
        .def_prop_ro("sample_count", &PyRenderer::sample_count)
        .def("info", &PyRenderer::info);
}
