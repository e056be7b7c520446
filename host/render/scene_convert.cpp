#include "host/render/scene_convert.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "gc_sampling.h"
#include "gc_tangent.h"
#include "host/bvh/task_pool.h"
#include "host/scene/triangle_sink.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"

namespace gc {
namespace {

glm::vec4 v4(const glm::vec3& v, float w = 0.0f) { return {v.x, v.y, v.z, w}; }
glm::vec4 v4(const Point3& p, float w = 0.0f) { return {p.x, p.y, p.z, w}; }
glm::vec4 v4(const Normal3& n, float w = 0.0f) { return {n.x, n.y, n.z, w}; }


std::uint32_t material_type(MaterialType type)
{
    switch (type) {
    case MaterialType::Lambert: return GC_MAT_LAMBERT;
    case MaterialType::Phong: return GC_MAT_PHONG;
    case MaterialType::Mirror: return GC_MAT_MIRROR;
    case MaterialType::Dielectric: return GC_MAT_DIELECTRIC;
    case MaterialType::Pbr: return GC_MAT_PBR;
    }
    return GC_MAT_LAMBERT;
}


// In double: the cross product's squared length is the fourth power of the triangle's size,
// which leaves float's range for triangles below ~1e-10 or above ~1e10 units across.
double triangle_area(const Point3& a, const Point3& b, const Point3& c)
{
    const glm::dvec3 e1 = glm::dvec3(b.glm()) - glm::dvec3(a.glm());
    const glm::dvec3 e2 = glm::dvec3(c.glm()) - glm::dvec3(a.glm());
    return 0.5 * glm::length(glm::cross(e1, e2));
}

// The largest |coordinate| of a triangle's corners: the scale of its hit points' rounding
// error, from which the kernels size the offset of rays that leave it (gc_spawn.h).
float corner_magnitude(const Point3& a, const Point3& b, const Point3& c)
{
    return unite(Bounds3(a, b), c).largest_abs_coordinate();
}

// Per-triangle tangent frame for normal maps: T = dP/du (unit, orthogonal to the face normal)
// and the sign w that makes B = w * cross(n, T) point up the image, i.e. along -dP/dv (glTF's
// uv origin is the top-left texel and a normal map's +Y is "up"). Solves the 2x2 system
// [dp1 dp2] = [T Bv] [du1 du2] (Lengyel, "Computing Tangent Space Basis Vectors for an
// Arbitrary Mesh", 2001), per triangle rather than per vertex: the kernel re-orthogonalises T
// against the interpolated normal. Zero when the uvs are degenerate (no normal mapping there).
glm::vec4 triangle_tangent(const Point3& p0, const Point3& p1, const Point3& p2, glm::vec2 t0, glm::vec2 t1,
                           glm::vec2 t2, const Normal3& ng)
{
    const glm::vec3 dp1 = (p1 - p0).glm();
    const glm::vec3 dp2 = (p2 - p0).glm();
    const glm::vec2 du1 = t1 - t0;
    const glm::vec2 du2 = t2 - t0;
    const float det = du1.x * du2.y - du1.y * du2.x;
    if (!(std::fabs(det) > 1e-20f) || !std::isfinite(det)) return glm::vec4(0.0f);
    const glm::vec3 n(ng.x, ng.y, ng.z);
    const glm::vec3 dpdu = (dp1 * du2.y - dp2 * du1.y) / det;
    const glm::vec3 dpdv = (dp2 * du1.x - dp1 * du2.x) / det;
    const glm::vec3 t = dpdu - n * glm::dot(n, dpdu);
    const float len = glm::length(t);
    if (!(len > 0.0f) || !std::isfinite(len)) return glm::vec4(0.0f);
    const float w = glm::dot(glm::cross(n, dpdu), dpdv) > 0.0f ? -1.0f : 1.0f;
    return glm::vec4(t / len, w);
}

std::uint32_t aov_code(AovKind kind)
{
    switch (kind) {
    case AovKind::Preview: return GC_AOV_PREVIEW;
    case AovKind::Albedo: return GC_AOV_ALBEDO;
    case AovKind::Normal: return GC_AOV_NORMAL;
    case AovKind::Depth: return GC_AOV_DEPTH;
    case AovKind::PrimitiveId: return GC_AOV_PRIMID;
    case AovKind::GuideAlbedo: return GC_AOV_GUIDE_ALBEDO;
    case AovKind::GuideNormal: return GC_AOV_GUIDE_NORMAL;
    }
    return GC_AOV_PREVIEW;
}

std::uint32_t integrator_code(IntegratorKind kind)
{
    switch (kind) {
    case IntegratorKind::Aov: return GC_INTEGRATOR_AOV;
    case IntegratorKind::Path: return GC_INTEGRATOR_PATH;
    case IntegratorKind::Whitted: return GC_INTEGRATOR_WHITTED;
    }
    return GC_INTEGRATOR_AOV;
}

// Triangles [begin, end) of make_triangle_attribs.
void fill_triangle_attribs(const Scene& scene, dev::GcTriangleAttribs* out, std::size_t begin, std::size_t end)
{
    const std::size_t n = scene.triangle_count();
    const bool has_uv = !scene.uvs.empty();
    const bool has_tangents = scene.tangents.size() == 3 * n;
    for (std::size_t i = begin; i < end; ++i) {
        dev::GcTriangleAttribs& a = out[i];
        a = dev::GcTriangleAttribs{};
        a.n0 = v4(scene.normals[3 * i + 0]);
        a.n1 = v4(scene.normals[3 * i + 1]);
        a.n2 = v4(scene.normals[3 * i + 2]);
        a.ng = v4(face_normal(scene.vertex(i, 0), scene.vertex(i, 1), scene.vertex(i, 2)),
                  corner_magnitude(scene.vertex(i, 0), scene.vertex(i, 1), scene.vertex(i, 2)));
        if (has_uv) {
            const glm::vec2 t0 = scene.uvs[3 * i + 0], t1 = scene.uvs[3 * i + 1], t2 = scene.uvs[3 * i + 2];
            a.uv01 = {t0.x, t0.y, t1.x, t1.y};
            a.uv2_u = t2.x;
            a.uv2_v = t2.y;
            a.tangent = triangle_tangent(scene.vertex(i, 0), scene.vertex(i, 1), scene.vertex(i, 2), t0, t1, t2,
                                         Normal3(a.ng.x, a.ng.y, a.ng.z));
        }
        a.material = scene.material_ids[i];
        a.flags = (has_uv ? GC_TRIF_HAS_UV : 0u) |
                  (i < scene.has_vertex_normals.size() && scene.has_vertex_normals[i] ? GC_TRIF_HAS_VERTEX_NORMALS : 0u);
        // The file's tangents, packed into the normals' spare .w (gc_tangent.h), when all three
        // corners have one; otherwise the kernel keeps the generated a.tangent.
        if (has_tangents && scene.tangents[3 * i].w != 0.0f && scene.tangents[3 * i + 1].w != 0.0f &&
            scene.tangents[3 * i + 2].w != 0.0f) {
            glm::vec4* corners[3] = {&a.n0, &a.n1, &a.n2};
            for (int j = 0; j < 3; ++j) {
                const glm::vec4& t = scene.tangents[3 * i + static_cast<std::size_t>(j)];
                corners[j]->w = dev::gc_as_float(dev::gc_tangent_encode(glm::vec3(t), t.w));
            }
            a.flags |= GC_TRIF_HAS_TANGENTS;
        }
    }
}

}  // namespace

BigArray<dev::GcTriangleAttribs> make_triangle_attribs(const Scene& scene)
{
    const std::size_t n = scene.triangle_count();
    BigArray<dev::GcTriangleAttribs> out(n);  // uninitialised: every element is written below
    // Chunks of 16k triangles (1.8 MB) keep the pool's overhead far below the work; scenes
    // of one chunk are filled on the calling thread.
    constexpr std::size_t kChunk = std::size_t{1} << 14;
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    const int threads = host_thread_count();
    if (chunks <= 1 || threads <= 1) {
        fill_triangle_attribs(scene, out.data(), 0, n);
        return out;
    }
    TaskPool pool(threads);
    pool.for_each(chunks, [&](std::size_t c) {
        fill_triangle_attribs(scene, out.data(), c * kChunk, std::min(n, (c + 1) * kChunk));
    });
    return out;
}

std::vector<dev::GcMaterial> make_materials(const Scene& scene)
{
    const TextureViews views = texture_views(scene);
    std::vector<dev::GcMaterial> out;
    out.reserve(scene.materials.size());
    for (const Material& m : scene.materials) {
        dev::GcMaterial d{};
        d.albedo = v4(m.albedo, m.opacity);
        d.specular = v4(m.specular, m.phong_exponent);
        d.emission = v4(m.emission, m.ior);
        d.pbr = {m.metallic, m.roughness, m.alpha_cutoff, m.transmission};
        d.type = material_type(m.type);
        const std::array<std::uint32_t, kMaterialSlots>& slots = views.material_slots[out.size()];
        d.albedo_texture = slots[kSlotAlbedo];
        d.metallic_roughness_texture = slots[kSlotMetallicRoughness];
        d.normal_texture = slots[kSlotNormal];
        d.normal_scale = m.normal_scale;
        d.emission_texture = slots[kSlotEmission];
        d.flags = (m.double_sided ? GC_MATF_TWO_SIDED : 0u) |
                  (m.alpha_mode == AlphaMode::Mask ? GC_MATF_ALPHA_MASK : 0u) |
                  (m.alpha_mode == AlphaMode::Blend ? GC_MATF_ALPHA_BLEND : 0u);
        // The KHR_materials_* layers (the layer flags are set for PBR materials only).
        const PbrLayers& l = m.layers;
        const bool pbr = m.type == MaterialType::Pbr;
        d.flags |= (pbr && l.clearcoat_on ? GC_MATF_CLEARCOAT : 0u) | (pbr && l.specular_on ? GC_MATF_SPECULAR : 0u) |
                   (pbr && l.sheen_on ? GC_MATF_SHEEN : 0u);
        // Roughness 0 keeps the thin-walled delta lobe (and its program and bits); a
        // metallicRoughness texture only scales the factor, so a factor of 0 stays smooth.
        if (pbr && m.transmission > 0.0f && m.roughness > 0.0f) d.flags |= GC_MATF_ROUGH_TRANSMISSION;
        // A volume makes the mesh a solid, not a thin wall: the transmission lobe refracts (the
        // microfacet one, a very sharp lobe at roughness 0) and the inside absorbs. The spec
        // applies the volume only to transmitted light, so without transmission it is dropped.
        if (pbr && l.volume_on && m.transmission > 0.0f) {
            d.flags |= GC_MATF_ROUGH_TRANSMISSION | GC_MATF_VOLUME;
            // Colour 0 would make sigma_a infinite and 0 * inf a NaN at t = 0: a floor of 1e-6.
            auto sigma = [&](float c) { return -std::log(std::max(c, 1e-6f)) / l.attenuation_distance; };
            d.absorption_r = sigma(l.attenuation_color.x);
            d.absorption_g = sigma(l.attenuation_color.y);
            d.absorption_b = sigma(l.attenuation_color.z);
        }
        if (pbr && l.specular_on) d.specular = v4(l.specular_color, d.specular.w);
        d.coat = {l.clearcoat, l.clearcoat_roughness, 0.0f, l.specular};
        d.sheen = v4(l.sheen_color, l.sheen_roughness);
        d.coat_texture = slots[kSlotClearcoat];
        d.coat_roughness_texture = slots[kSlotClearcoatRoughness];
        d.specular_texture = slots[kSlotSpecular];
        d.specular_color_texture = slots[kSlotSpecularColor];
        d.sheen_color_texture = slots[kSlotSheenColor];
        d.sheen_roughness_texture = slots[kSlotSheenRoughness];
        d.transmission_texture = slots[kSlotTransmission];
        d.coat_normal_texture = slots[kSlotClearcoatNormal];
        d.coat_normal_scale = l.clearcoat_normal_scale;
        out.push_back(d);
    }
    return out;
}

std::array<glm::vec3, 2> uv_transform_rows(const UvTransform& t)
{
    // In double, then rounded once: the rows are uploaded, so every device reads these bits.
    const double c = std::cos(static_cast<double>(t.rotation));
    const double s = std::sin(static_cast<double>(t.rotation));
    const double sx = t.scale.x, sy = t.scale.y;
    return {glm::vec3(static_cast<float>(c * sx), static_cast<float>(s * sy), t.offset.x),
            glm::vec3(static_cast<float>(-s * sx), static_cast<float>(c * sy), t.offset.y)};
}

TextureViews texture_views(const Scene& scene)
{
    TextureViews out;
    std::size_t total = 0;
    for (const Texture& t : scene.textures) total += t.device_words();
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw InputError(scene.source_path + ": textures hold " + std::to_string(total) +
                         " texels, more than the 2^32 a texel index can address");
    std::uint32_t offset = 0;
    for (const Texture& t : scene.textures) {
        dev::GcTexture d{};
        d.offset = offset;
        d.width = static_cast<std::uint32_t>(t.width);
        d.height = static_cast<std::uint32_t>(t.height);
        auto wrap_flags = [](WrapMode mode, std::uint32_t clamp_flag, std::uint32_t mirror_flag) {
            return mode == WrapMode::ClampToEdge ? clamp_flag : (mode == WrapMode::MirroredRepeat ? mirror_flag : 0u);
        };
        const bool linear = !t.linear.empty();
        d.flags = (linear ? GC_TEXF_FLOAT : (t.srgb ? GC_TEXF_SRGB : 0u)) | wrap_flags(t.wrap_s, GC_TEXF_CLAMP_S, GC_TEXF_MIRROR_S) |
                  wrap_flags(t.wrap_t, GC_TEXF_CLAMP_T, GC_TEXF_MIRROR_T) | (t.nearest ? GC_TEXF_NEAREST : 0u);
        out.views.push_back(d);
        offset += static_cast<std::uint32_t>(t.device_words());
    }
    // Transformed views, deduplicated on the texture and the bits of the rows uploaded.
    std::map<std::pair<int, std::array<std::uint32_t, 6>>, std::uint32_t> transformed;
    auto view = [&](int texture, const UvTransform& transform) -> std::uint32_t {
        if (texture < 0) return GC_INVALID;
        if (static_cast<std::size_t>(texture) >= scene.textures.size())
            throw InputError(scene.name_for_messages() + ": a material names texture " + std::to_string(texture) +
                             " of " + std::to_string(scene.textures.size()));
        if (transform.is_identity()) return static_cast<std::uint32_t>(texture);
        const std::array<glm::vec3, 2> rows = uv_transform_rows(transform);
        const std::array<std::uint32_t, 6> bits = {std::bit_cast<std::uint32_t>(rows[0].x), std::bit_cast<std::uint32_t>(rows[0].y),
                                                   std::bit_cast<std::uint32_t>(rows[0].z), std::bit_cast<std::uint32_t>(rows[1].x),
                                                   std::bit_cast<std::uint32_t>(rows[1].y), std::bit_cast<std::uint32_t>(rows[1].z)};
        const auto [it, added] = transformed.try_emplace({texture, bits}, static_cast<std::uint32_t>(out.views.size()));
        if (added) {
            dev::GcTexture d = out.views[static_cast<std::size_t>(texture)];
            d.flags |= GC_TEXF_TRANSFORM;
            d.uv_u = glm::vec4(rows[0], 0.0f);
            d.uv_v = glm::vec4(rows[1], 0.0f);
            out.views.push_back(d);
        }
        return it->second;
    };
    out.material_slots.reserve(scene.materials.size());
    for (const Material& m : scene.materials) {
        const PbrLayers& l = m.layers;
        auto ref = [&](const TextureRef& r) { return view(r.texture, r.uv); };
        out.material_slots.push_back({view(m.albedo_texture, m.albedo_uv),
                                      view(m.metallic_roughness_texture, m.metallic_roughness_uv),
                                      view(m.normal_texture, m.normal_uv), view(m.emission_texture, m.emission_uv),
                                      ref(l.clearcoat_texture), ref(l.clearcoat_roughness_texture),
                                      ref(l.specular_texture), ref(l.specular_color_texture),
                                      ref(l.sheen_color_texture), ref(l.sheen_roughness_texture),
                                      ref(l.transmission_texture), ref(l.clearcoat_normal_texture)});
    }
    return out;
}

DeviceTextures make_textures(const Scene& scene)
{
    DeviceTextures out;
    out.textures = texture_views(scene).views;
    std::size_t total = 0;
    for (const Texture& t : scene.textures) total += t.device_words();
    out.texels.reserve(total);
    for (const Texture& t : scene.textures) {
        if (t.linear.empty()) {
            out.texels.insert(out.texels.end(), t.texels.begin(), t.texels.end());
            continue;
        }
        for (const glm::vec4& v : t.linear)
            for (int c = 0; c < 4; ++c) out.texels.push_back(std::bit_cast<std::uint32_t>(v[c]));
    }
    return out;
}

std::vector<dev::GcPointLight> make_point_lights(const Scene& scene)
{
    std::vector<dev::GcPointLight> out;
    for (const PointLight& l : scene.point_lights) out.push_back({v4(l.position), v4(l.intensity)});
    return out;
}

std::vector<dev::GcEmitter> make_emitters(const Scene& scene, std::uint32_t first_triangle)
{
    std::vector<dev::GcEmitter> out;
    double total_power = 0.0;
    for (std::uint32_t tri : scene.emissive_triangles()) {
        if (tri < first_triangle) continue;
        const Point3 a = scene.vertex(tri, 0), b = scene.vertex(tri, 1), c = scene.vertex(tri, 2);
        const float area = static_cast<float>(triangle_area(a, b, c));
        const Material& m = scene.materials[scene.material_ids[tri]];
        const double power = static_cast<double>(area) * dev::gc_luminance(m.emission);
        if (!(area > 0.0f) || !std::isfinite(area) || !(power > 0.0)) continue;
        dev::GcEmitter e{};
        e.v0 = v4(a);
        e.v1 = v4(b);
        e.v2 = v4(c);
        e.triangle = tri;
        e.area = area;
        e.pmf = static_cast<float>(power);  // normalised below
        total_power += power;
        out.push_back(e);
    }
    double running = 0.0;
    for (dev::GcEmitter& e : out) {
        const double p = static_cast<double>(e.pmf) / total_power;
        running += p;
        e.pmf = static_cast<float>(p);
        e.cdf = static_cast<float>(running);
    }
    if (!out.empty()) out.back().cdf = 1.0f;
    return out;
}

float total_emitter_power(const Scene& scene, std::span<const dev::GcEmitter> emitters)
{
    double total = 0.0;
    for (const dev::GcEmitter& e : emitters) {
        const glm::vec3 le = scene.materials[scene.material_ids[e.triangle]].emission;
        total += static_cast<double>(e.area) * dev::gc_luminance(le);
    }
    return static_cast<float>(total);
}

float total_emitter_power(const Scene& scene) { return total_emitter_power(scene, make_emitters(scene)); }

SceneSummary summarize(const Scene& scene, std::span<const dev::GcEmitter> emitters, std::size_t texture_views)
{
    SceneSummary summary;
    summary.triangles = static_cast<std::uint32_t>(scene.triangle_count());
    summary.emitters = static_cast<std::uint32_t>(emitters.size());
    summary.point_lights = static_cast<std::uint32_t>(scene.point_lights.size());
    summary.textures = static_cast<std::uint32_t>(texture_views);
    summary.emitter_power = total_emitter_power(scene, emitters);
    return summary;
}

SceneSummary summarize(const Scene& scene)
{
    return summarize(scene, make_emitters(scene), texture_views(scene).views.size());
}

dev::GcRenderParams make_render_params(const SceneSummary& scene, const Camera& camera, const RenderSettings& settings)
{
    dev::GcRenderParams p{};
    p.camera = make_camera(camera, settings.width, settings.height);
    p.env_radiance = glm::vec4(settings.env_radiance, 0.0f);
    p.width = static_cast<std::uint32_t>(settings.width);
    p.height = static_cast<std::uint32_t>(settings.height);
    p.seed = settings.seed;
    p.flags = settings.sampler == SamplerKind::Sobol ? GC_RENDER_SOBOL : 0u;
    p.max_depth = settings.max_depth;
    p.integrator = integrator_code(settings.integrator);
    p.aov = aov_code(settings.aov);
    p.num_triangles = scene.triangles;
    p.num_emitters = scene.emitters;
    p.num_point_lights = scene.point_lights;
    p.num_textures = scene.textures;
    p.rr_depth = settings.rr_depth;
    p.emitter_power = scene.emitter_power;
    p.pixel_offset = 0;
    p.pixel_count = p.width * p.height;
    p.samples_in_pass = 1;
    p.pixels_per_item = 1;
    return p;
}

dev::GcRenderParams make_render_params(const Scene& scene, const Camera& camera, const RenderSettings& settings)
{
    return make_render_params(summarize(scene), camera, settings);
}

void set_environment_map(dev::GcRenderParams& params, const RenderSettings& settings, std::uint32_t width,
                         std::uint32_t height)
{
    if (settings.env_map_path.empty()) return;
    params.env_width = width;
    params.env_height = height;
    if (width == 0) params.env_radiance = glm::vec4(0.0f);
}

dev::GcCamera make_camera(const Camera& camera, int width, int height)
{
    // In double (unit_direction): float's squared lengths fail for scenes below ~1e-19 or
    // above ~1e19 across, which resolve_camera accepts.
    const Vec3 forward = unit_direction(camera.look_from, camera.look_at);
    Vec3 right = cross(forward, unit_vector(camera.up));
    if (!(length(right) > 1e-8f)) {
        // up parallel to the view direction: pick any perpendicular up rather than NaNs.
        right = cross(forward, std::fabs(forward.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0));
    }
    right = normalize(right);
    const Vec3 up = cross(right, forward);
    const float tan_half = std::tan(0.5f * camera.vfov_degrees * 3.14159265358979f / 180.0f);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    dev::GcCamera d{};
    // The thin lens rides in the w components (gc_camera_sample).
    const float focus = camera.focus_distance > 0.0f ? camera.focus_distance
                                                     : float(dot(camera.look_at - camera.look_from, forward));
    d.origin = v4(camera.look_from, camera.aperture_radius);
    d.forward = v4(forward.glm(), camera.aperture_radius > 0.0f ? focus : 0.0f);
    d.right = v4((right * (tan_half * aspect)).glm());
    d.up = v4((up * tan_half).glm());
    return d;
}

}  // namespace gc
