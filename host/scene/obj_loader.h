// Wavefront .obj + .mtl -> Scene, through tinyobjloader after obj_validate's checks.
#pragma once

#include <filesystem>

#include "host/scene/load_options.h"
#include "host/scene/scene.h"

namespace gc {

// Material mapping (the Mitsuba reference conventions, /work/shared/refs/README.md):
//   illum 0-2            Lambert(Kd); illum 2 with Ks > 0 -> Phong(Kd, Ks, Ns), kd+ks <= 1 enforced
//                        (unless options.phong_as_lambert)
//   illum 3, 5, 8        Mirror: albedo = Kd (diffuse part), specular = Ks (mirror reflectance)
//   illum 4, 6, 7, 9     Dielectric with ior = Ni
//   Ke                   emission (radiance); d -> opacity; map_Kd -> albedo texture (sRGB)
// Faces without a material get a Lambert 0.5 material named "default". Polygons are
// fan-triangulated (v0, vi, vi+1). UVs follow the glTF convention ((0,0) = top-left texel),
// so OBJ's v (origin bottom-left) is stored as 1 - v.
Scene load_obj(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace gc
