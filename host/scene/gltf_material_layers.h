// The KHR_materials_clearcoat, _specular and _sheen objects of one glTF material, read
// into PbrLayers. Values the specifications do not allow (a factor that is not a number, out
// of [0, 1], a colour that is not three non-negative numbers, a texture reference without an
// integer index) are refused with an InputError naming the material and the key.
#pragma once

#include <functional>
#include <string>

#include "host/scene/scene.h"

namespace tinygltf {
class Value;
}

namespace gc {

// The scene texture a textureInfo object `info` names, in the colour space asked for, with its
// KHR_texture_transform; `slot` names it for messages ("KHR_materials_clearcoat clearcoatTexture").
using LayerTextureResolver = std::function<TextureRef(const tinygltf::Value& info, bool srgb, const std::string& slot)>;

// `extension` is the material's extension object; `where` names the file and the material for
// messages. Sets that extension's fields of `layers`.
void read_clearcoat(const tinygltf::Value& extension, const std::string& where, const LayerTextureResolver& texture,
                    PbrLayers& layers);
void read_specular(const tinygltf::Value& extension, const std::string& where, const LayerTextureResolver& texture,
                   PbrLayers& layers);
// KHR_materials_transmission's transmissionTexture (its factor is the material's transmission).
void read_transmission_texture(const tinygltf::Value& extension, const std::string& where,
                               const LayerTextureResolver& texture, PbrLayers& layers);
// KHR_materials_volume: attenuationDistance must be > 0, attenuationColor in [0, 1].
void read_volume(const tinygltf::Value& extension, const std::string& where, PbrLayers& layers);
void read_sheen(const tinygltf::Value& extension, const std::string& where, const LayerTextureResolver& texture,
                PbrLayers& layers);

}  // namespace gc
