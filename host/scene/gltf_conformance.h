// What the glTF 2.0 spec asks of a loader before it reads an asset: the asset's version must
// be one it implements (asset.version 2.x, asset.minVersion at most 2.0), and so must every
// extension the asset lists in extensionsRequired. Read from the JSON before tinygltf parses
// the rest, so a refused asset's buffers and images are never loaded.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gc {

// The glTF extensions gltf_loader.cpp implements, and the only place they are listed:
//   KHR_lights_punctual               point lights (spot and directional lights are skipped,
//                                     with a warning)
//   KHR_materials_clearcoat           factor, roughness and their textures (gc_bsdf.h); the
//                                     coat normal texture is ignored with a warning
//   KHR_materials_emissive_strength   emissiveStrength
//   KHR_materials_ior                 ior
//   KHR_materials_sheen               colour, roughness and their textures (Charlie sheen)
//   KHR_materials_specular            factor, colour and their textures
//   KHR_materials_transmission        transmissionFactor and transmissionTexture (R); refracting
//                                     (GGX) when rough or with a volume, else thin-walled (gc_bsdf.h)
//   KHR_materials_volume              attenuationColor, attenuationDistance (thicknessFactor is
//                                     for rasterizers and not read)
//   KHR_mesh_quantization             integer POSITION/NORMAL/TANGENT/TEXCOORD accessors
//                                     (gltf_accessor.cpp)
//   KHR_texture_transform             offset, rotation, scale, texCoord on every texture slot
inline constexpr std::array<std::string_view, 10> k_supported_gltf_extensions = {
    "KHR_lights_punctual",        "KHR_materials_clearcoat", "KHR_materials_emissive_strength",
    "KHR_materials_ior",          "KHR_materials_sheen",     "KHR_materials_specular",
    "KHR_materials_transmission", "KHR_materials_volume",    "KHR_mesh_quantization",
    "KHR_texture_transform"};

bool gltf_extension_supported(std::string_view name);

// The names among `names` that k_supported_gltf_extensions lacks, in order, without repeats.
std::vector<std::string> unsupported_gltf_extensions(const std::vector<std::string>& names);

// The top-level declarations of a glTF document.
struct GltfDeclarations {
    std::optional<std::string> version;      // asset.version, when it is a string
    std::optional<std::string> min_version;  // asset.minVersion, when present
    std::vector<std::string> extensions_required;
    std::vector<std::string> extensions_used;
};

// Reads them from the JSON text of a .gltf file or of a .glb's JSON chunk, keeping nothing
// else. std::nullopt when the text is not a JSON object: tinygltf then reports why.
std::optional<GltfDeclarations> read_gltf_declarations(std::string_view json_text);

// Throws InputError naming `file_name` and what it declares that this loader cannot honour: a
// missing or malformed asset.version, a major version other than 2, an asset.minVersion above
// 2.0, or required extensions outside k_supported_gltf_extensions (all of them named).
void check_gltf_declarations(const GltfDeclarations& declared, const std::string& file_name);

// One warning naming the extensions the asset uses but this loader ignores; none when it
// uses only supported ones.
void warn_unsupported_gltf_extensions(const std::vector<std::string>& extensions_used, const std::string& file_name);

}  // namespace gc
