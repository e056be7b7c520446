#include "host/scene/gltf_material_layers.h"

#include <cmath>
#include <limits>

#include <tiny_gltf.h>

#include "host/util/error.h"

namespace gc {
namespace {

// A factor in [lo, hi] (the specifications' ranges), `fallback` when absent.
float factor(const tinygltf::Value& ext, const char* key, float fallback, const std::string& where, float lo = 0.0f,
             float hi = 1.0f)
{
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsNumber()) throw InputError(where + ": " + key + " is not a number");
    const double d = v.GetNumberAsDouble();
    if (!(d >= lo && d <= hi))
        throw InputError(where + ": " + key + " = " + std::to_string(d) + " is outside [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]");
    return static_cast<float>(d);
}

glm::vec3 colour(const tinygltf::Value& ext, const char* key, glm::vec3 fallback, const std::string& where)
{
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 3) throw InputError(where + ": " + key + " is not an array of three numbers");
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const tinygltf::Value& c = v.Get(i);
        const double d = c.IsNumber() ? c.GetNumberAsDouble() : -1.0;
        if (!(d >= 0.0) || !std::isfinite(static_cast<float>(d)))
            throw InputError(where + ": " + key + " holds a value that is not a finite non-negative number");
        out[i] = static_cast<float>(d);
    }
    return out;
}

TextureRef texture_ref(const tinygltf::Value& ext, const char* extension, const char* key, bool srgb,
                       const std::string& where, const LayerTextureResolver& texture)
{
    if (!ext.Has(key)) return {};
    const tinygltf::Value& info = ext.Get(key);
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt() || info.Get("index").GetNumberAsInt() < 0)
        throw InputError(where + ": " + extension + " " + key + " has no non-negative integer index");
    return texture(info, srgb, std::string(extension) + " " + key);
}

}  // namespace

void read_clearcoat(const tinygltf::Value& ext, const std::string& where, const LayerTextureResolver& texture,
                    PbrLayers& layers)
{
    const std::string ctx = where + ": KHR_materials_clearcoat";
    if (!ext.IsObject()) throw InputError(ctx + " is not an object");
    layers.clearcoat_on = true;
    layers.clearcoat = factor(ext, "clearcoatFactor", 0.0f, ctx);
    layers.clearcoat_roughness = factor(ext, "clearcoatRoughnessFactor", 0.0f, ctx);
    const char* name = "KHR_materials_clearcoat";
    layers.clearcoat_texture = texture_ref(ext, name, "clearcoatTexture", false, where, texture);
    layers.clearcoat_roughness_texture = texture_ref(ext, name, "clearcoatRoughnessTexture", false, where, texture);
    layers.clearcoat_normal_texture = texture_ref(ext, name, "clearcoatNormalTexture", false, where, texture);
    if (layers.clearcoat_normal_texture.texture >= 0) {
        const tinygltf::Value& info = ext.Get("clearcoatNormalTexture");
        layers.clearcoat_normal_scale = factor(info, "scale", 1.0f, ctx + " clearcoatNormalTexture",
                                               -std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
    }
}

void read_specular(const tinygltf::Value& ext, const std::string& where, const LayerTextureResolver& texture,
                   PbrLayers& layers)
{
    const std::string ctx = where + ": KHR_materials_specular";
    if (!ext.IsObject()) throw InputError(ctx + " is not an object");
    layers.specular_on = true;
    layers.specular = factor(ext, "specularFactor", 1.0f, ctx);
    layers.specular_color = colour(ext, "specularColorFactor", glm::vec3(1.0f), ctx);
    const char* name = "KHR_materials_specular";
    layers.specular_texture = texture_ref(ext, name, "specularTexture", false, where, texture);
    layers.specular_color_texture = texture_ref(ext, name, "specularColorTexture", true, where, texture);
}

void read_volume(const tinygltf::Value& ext, const std::string& where, PbrLayers& layers)
{
    const std::string ctx = where + ": KHR_materials_volume";
    if (!ext.IsObject()) throw InputError(ctx + " is not an object");
    layers.volume_on = true;
    layers.attenuation_color = colour(ext, "attenuationColor", glm::vec3(1.0f), ctx);
    for (int i = 0; i < 3; ++i)
        if (layers.attenuation_color[i] > 1.0f)
            throw InputError(ctx + ": attenuationColor holds a value above 1");
    if (ext.Has("attenuationDistance")) {
        const tinygltf::Value& v = ext.Get("attenuationDistance");
        const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
        if (!(d > 0.0)) throw InputError(ctx + ": attenuationDistance is not a positive number");
        layers.attenuation_distance = static_cast<float>(d);
    }
    // thicknessFactor and thicknessTexture are not read: they let a rasterizer guess the path
    // length through the mesh, which a path tracer measures by tracing the ray to the far side.
}

void read_transmission_texture(const tinygltf::Value& ext, const std::string& where, const LayerTextureResolver& texture,
                               PbrLayers& layers)
{
    if (!ext.IsObject()) throw InputError(where + ": KHR_materials_transmission is not an object");
    layers.transmission_texture =
        texture_ref(ext, "KHR_materials_transmission", "transmissionTexture", false, where, texture);
}

void read_sheen(const tinygltf::Value& ext, const std::string& where, const LayerTextureResolver& texture,
                PbrLayers& layers)
{
    const std::string ctx = where + ": KHR_materials_sheen";
    if (!ext.IsObject()) throw InputError(ctx + " is not an object");
    layers.sheen_on = true;
    layers.sheen_color = colour(ext, "sheenColorFactor", glm::vec3(0.0f), ctx);
    layers.sheen_roughness = factor(ext, "sheenRoughnessFactor", 0.0f, ctx);
    const char* name = "KHR_materials_sheen";
    layers.sheen_color_texture = texture_ref(ext, name, "sheenColorTexture", true, where, texture);
    layers.sheen_roughness_texture = texture_ref(ext, name, "sheenRoughnessTexture", false, where, texture);
}

}  // namespace gc
