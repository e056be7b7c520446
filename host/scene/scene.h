// The renderer's one scene representation: flat, unindexed triangle arrays plus materials,
// textures, lights and an optional camera. Loaders fill it; the BVH builder and the device
// upload read it. Everything is in world space and linear RGB.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host/math/affine.h"
#include "host/math/bounds3.h"

namespace gc {

enum class MaterialType : std::uint32_t { Lambert, Phong, Mirror, Dielectric, Pbr };
enum class AlphaMode : std::uint32_t { Opaque, Mask, Blend };
enum class WrapMode : std::uint32_t { Repeat, ClampToEdge, MirroredRepeat };

// glTF KHR_texture_transform on one material slot: the slot reads its texture at
// T(offset) * R(rotation) * S(scale) applied to the mesh's uv. Identity by default.
struct UvTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;   // radians; glTF's sense: the uvs turn counter-clockwise
    glm::vec2 scale{1.0f};

    bool is_identity() const
    {
        return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
    }
    bool operator==(const UvTransform&) const = default;
};

// A texture slot of a KHR_materials_* extension: the scene texture and its uv transform.
struct TextureRef {
    int texture = -1;  // index into Scene::textures, -1 = none
    UvTransform uv;
    bool operator==(const TextureRef&) const = default;
};

// The KHR_materials_* layers over the metallic-roughness base (gc_bsdf.h gives the model).
// Each is off unless its extension is on the material; the defaults are the extensions'.
struct PbrLayers {
    bool clearcoat_on = false;       // KHR_materials_clearcoat
    float clearcoat = 0.0f;          // clearcoatFactor
    float clearcoat_roughness = 0.0f;
    TextureRef clearcoat_texture;    // R: factor
    TextureRef clearcoat_roughness_texture; // G: roughness
    TextureRef clearcoat_normal_texture; // the coat's own tangent-space normal map (linear)
    float clearcoat_normal_scale = 1.0f; // its normalTextureInfo scale
    bool specular_on = false;        // KHR_materials_specular
    float specular = 1.0f;           // specularFactor
    glm::vec3 specular_color{1.0f};  // specularColorFactor (linear)
    TextureRef specular_texture;     // A: factor
    TextureRef specular_color_texture; // sRGB rgb: colour
    bool sheen_on = false;           // KHR_materials_sheen
    glm::vec3 sheen_color{0.0f};
    float sheen_roughness = 0.0f;
    TextureRef sheen_color_texture;  // sRGB rgb
    TextureRef sheen_roughness_texture; // A
    TextureRef transmission_texture; // KHR_materials_transmission transmissionTexture, R: factor
    bool volume_on = false;          // KHR_materials_volume (thicknessFactor is not kept: see read_volume)
    glm::vec3 attenuation_color{1.0f};
    float attenuation_distance = std::numeric_limits<float>::infinity();
    bool operator==(const PbrLayers&) const = default;
};

struct Material {
    std::string name = "default";
    MaterialType type = MaterialType::Lambert;
    glm::vec3 albedo{0.5f};      // Kd / baseColorFactor (linear)
    glm::vec3 specular{0.0f};    // Ks (Phong lobe, or mirror reflectance)
    float phong_exponent = 1.0f; // Ns
    glm::vec3 emission{0.0f};    // Ke / emissiveFactor * strength: radiance
    float ior = 1.5f;            // Ni
    float opacity = 1.0f;        // d / baseColor alpha
    float metallic = 0.0f;
    float roughness = 1.0f;
    float transmission = 0.0f;
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;
    bool double_sided = false;
    int albedo_texture = -1;     // index into Scene::textures, -1 = none
    int metallic_roughness_texture = -1;
    int normal_texture = -1;
    float normal_scale = 1.0f;   // glTF normalTexture.scale (tangent-space xy factor)
    int emission_texture = -1;
    // Each slot's uv transform (KHR_texture_transform); the device gets one texture view per
    // distinct (texture, transform) pair (scene_convert.h, texture_views).
    UvTransform albedo_uv;
    UvTransform metallic_roughness_uv;
    UvTransform normal_uv;
    UvTransform emission_uv;
    PbrLayers layers;            // glTF KHR_materials_* (Pbr only)

    bool is_emissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

struct Texture {
    std::string name;            // file name or "<gltf image N>", for messages
    int width = 0;
    int height = 0;
    std::vector<std::uint32_t> texels; // RGBA8, R in the low byte, row 0 = top of the image
    // Where not empty, the texels as linear RGBA floats (same order), which the device reads
    // instead of `texels`: a texture an optimiser edits (scene_params.h) keeps its precision.
    std::vector<glm::vec4> linear;
    bool srgb = true;            // colour textures are sRGB-encoded; data textures are not
    WrapMode wrap_s = WrapMode::Repeat;
    WrapMode wrap_t = WrapMode::Repeat;
    bool nearest = false;

    // 32-bit words the texture occupies in the device's texel buffer: one per RGBA8 texel,
    // four per linear float texel.
    std::size_t device_words() const { return linear.empty() ? texels.size() : 4 * linear.size(); }
};

struct Camera {
    Point3 look_from{0, 0, 1};
    Point3 look_at{0, 0, 0};
    Vec3 up{0, 1, 0};
    float vfov_degrees = 40.0f; // full vertical field of view
    float aperture_radius = 0.0f; // thin lens (gc_camera.h); 0 = pinhole
    float focus_distance = 0.0f;  // along the view axis; 0 = to look_at
};

struct PointLight {
    Point3 position;
    // Radiant intensity, W/sr per channel. glTF gives candela; we take 1 cd as 1 W/sr (no
    // 683 lm/W factor), so a scene's lights keep the relative brightness its author saw.
    glm::vec3 intensity{1.0f};
};

struct Scene {
    // Three entries per triangle, in triangle order. normals are always filled: the face
    // normal at each corner when the file gives none (then has_vertex_normals is false).
    std::vector<Point3> positions;
    std::vector<Normal3> normals;
    // Texture coordinates follow glTF: (0, 0) is the top-left texel (OBJ's v becomes 1 - v).
    std::vector<glm::vec2> uvs;                 // three per triangle, or empty
    // The file's per-vertex tangents (glTF TANGENT), three per triangle, or empty: xyz unit,
    // w the bitangent sign (+1 or -1: B = w * cross(N, T)); all zero at a corner without one.
    std::vector<glm::vec4> tangents;
    std::vector<std::uint32_t> material_ids;    // one per triangle, index into materials
    std::vector<std::uint8_t> has_vertex_normals; // one per triangle (0/1)

    std::vector<Material> materials;            // never empty once loaded
    std::vector<Texture> textures;
    std::vector<PointLight> point_lights;
    std::optional<Camera> camera;               // the file's camera, if it has one

    std::string source_path;                    // the file it came from, for messages

    // What error messages call the scene: its file, or a note that it has none.
    std::string name_for_messages() const
    {
        return source_path.empty() ? std::string("<scene built in memory>") : source_path;
    }
    std::size_t triangle_count() const { return material_ids.size(); }
    Point3 vertex(std::size_t tri, int corner) const { return positions[3 * tri + corner]; }

    Bounds3 bounds() const
    {
        Bounds3 b;
        for (const Point3& p : positions) b = unite(b, p);
        return b;
    }

    // Scene triangle indices whose material emits, in triangle order.
    std::vector<std::uint32_t> emissive_triangles() const
    {
        std::vector<std::uint32_t> out;
        for (std::size_t i = 0; i < triangle_count(); ++i)
            if (materials[material_ids[i]].is_emissive()) out.push_back(static_cast<std::uint32_t>(i));
        return out;
    }
};

}  // namespace gc
