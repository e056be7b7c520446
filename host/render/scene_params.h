// The scene's differentiable parameters by name, as the gradient pass (gradients.h) reports
// them and as an optimiser edits them:
//
//     materials/<m>/base_color   (3)  Lambert/Phong Kd, glTF baseColorFactor, mirror's diffuse part
//     materials/<m>/emission     (3)  Ke / emissiveFactor * strength, of materials that emit
//     materials/<m>/specular     (3)  Phong's Ks, the mirror's reflectance
//     materials/<m>/phong_exponent (1)  Phong's Ns
//     materials/<m>/metallic     (1)  glTF metallicFactor
//     materials/<m>/roughness    (1)  glTF roughnessFactor
//     environment/radiance       (3)  the constant environment, or the environment map's scale
//     textures/<i>/texels        (h, w, 4)  the texels of a base-colour, metallic-roughness or
//                                           emissive texture, linear (decoded from sRGB); the
//                                           gradient's alpha is 0 (not differentiated).
//                                           Once set, the texture is stored as linear floats.
//
// <m> is the material's name where it is unique in the scene, else its index. Geometry, the
// camera and indices of refraction are not differentiable (the adjoint does not sample
// visibility changes, and the primal detaches refraction directions); asking for them, or for
// a parameter the adjoint does not differentiate yet, is a UsageError that says so.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "host/cl/context.h"
#include "host/render/device_scene.h"
#include "host/render/renderer.h"
#include "host/scene/scene.h"

namespace gc {

struct ParamInfo {
    std::string name;
    std::vector<std::size_t> shape;
};

// What a parameter name refers to.
struct ParamRef {
    enum class Kind {
        BaseColor,
        Emission,
        Specular,
        PhongExponent,
        Metallic,
        Roughness,
        EnvRadiance,
        Texels
    };
    Kind kind = Kind::BaseColor;
    std::uint32_t material = 0;  // the material fields
    std::uint32_t texture = 0;   // Texels
};

// Every differentiable parameter of `scene`, in a fixed order (materials in scene order, the
// environment, then textures in scene order).
std::vector<ParamInfo> list_params(const Scene& scene);
// The parameter `name` names in `scene`, or UsageError saying why there is none.
ParamRef resolve_param(const Scene& scene, std::string_view name);

// A texture's texels as linear RGBA floats, row-major from the top row (what
// textures/<i>/texels reads).
std::vector<float> texels_linear(const Texture& texture);

// Reads and edits a scene's parameters where they live: the host scene and its device copy
// (DeviceScene::update_materials, so renderers of it restart their films) and the renderer's
// environment.
class SceneParams {
public:
    SceneParams(const cl::Context& context, Scene& scene, DeviceScene& device, Renderer& renderer);

    std::vector<ParamInfo> list() const { return list_params(m_scene); }
    std::vector<float> get(std::string_view name) const;
    // UsageError if `value` does not have the parameter's size.
    void set(std::string_view name, std::span<const float> value);

private:
    const cl::Context& m_context;
    Scene& m_scene;
    DeviceScene& m_device;
    Renderer& m_renderer;
};

}  // namespace gc
