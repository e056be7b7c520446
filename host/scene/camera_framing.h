// Choosing the view: the file's camera, a framed default when it has none, and the user's
// overrides on top.
#pragma once

#include <optional>

#include "host/scene/scene.h"

namespace gc {

struct CameraOverrides {
    std::optional<Point3> look_from;
    std::optional<Point3> look_at;
    std::optional<Vec3> up;
    std::optional<float> fov; // full vertical field of view, degrees
    std::optional<float> aperture_radius;  // thin lens: files have no aperture, so flags only
    std::optional<float> focus_distance;
};

// Looks at the centre of the scene's bounds from +Z (down -Z, +Y up) with a 40-degree
// vertical field of view, from the nearest distance at which every corner of the bounding
// box projects inside the view with a 5% margin (for images at least as wide as they are
// tall). An empty scene gives the default Camera. Works at any scale single precision can
// hold; throws InputError naming the scene's file and its extent when no float camera can
// frame it (the camera would stand past float's range, or so close to the centre that its
// position rounds onto the centre's).
Camera frame_camera(const Scene& scene);
// The same for the world bounds `bounds` (an instanced scene's, whose triangles are its
// meshes in object space); `scene` names the file in errors.
Camera frame_camera(const Scene& scene, const Bounds3& bounds);

// The file's camera (or frame_camera's, unless the overrides give both look_from and
// look_at) with the overrides applied; the framing uses `world_bounds` where given (an
// instanced scene's), else the scene's triangles. Throws UsageError when the result is
// unusable: look_from == look_at, up parallel to the view direction, a zero up, or a field of
// view outside (0, 180) degrees.
Camera resolve_camera(const Scene& scene, const CameraOverrides& overrides,
                      const std::optional<Bounds3>& world_bounds = std::nullopt);

}  // namespace gc
