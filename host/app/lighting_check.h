// Whether a render can show anything: a path-traced or Whitted image of a scene with no light
// source under a black environment is black, which users otherwise discover only after the
// render (glTF models are often shipped without lights, expecting a viewer's environment).
#pragma once

#include <optional>
#include <string>

#include "host/render/render_settings.h"
#include "host/scene/scene.h"

namespace gc {

// Whether anything lights `scene` under `settings`: an emissive triangle, a point light, an
// environment map or a non-zero --env.
bool has_light(const Scene& scene, const RenderSettings& settings);

// The warning for a render that can only come out black, or nothing when something lights
// it: an emissive triangle, a point light, an environment map or a non-zero --env. The AOV
// integrator needs no light.
std::optional<std::string> unlit_scene_warning(const Scene& scene, const RenderSettings& settings);

}  // namespace gc
