#include "host/scene/camera_framing.h"

#include <cmath>
#include <string>

#include "host/util/error.h"

namespace gc {

namespace {

constexpr float k_default_fov_degrees = 40.0f;
// The box's projection may use 1 / k_margin of the half-field: a thin border of background.
constexpr float k_margin = 1.05f;

}  // namespace

// Looks down -Z at the centre of the bounds, from the nearest distance at which every corner
// of the bounding box projects inside the view. Fitting the corners rather than the bounding
// sphere frames boxy scenes (a Cornell box, a room) the way a person would: the open side
// fills the image instead of floating in a black border.
Camera frame_camera(const Scene& scene)
{
    Camera camera;
    camera.vfov_degrees = k_default_fov_degrees;
    const Bounds3 b = scene.bounds();
    if (b.empty()) return camera;
    const Point3 center = b.centroid();
    const Vec3 half_extent = 0.5f * b.diagonal();
    const float tan_half = std::tan(0.5f * k_default_fov_degrees * 3.14159265f / 180.0f);
    // Corner (dx, dy, dz) relative to the centre, camera at distance d on +Z: it is inside the
    // (square, or wider) view when max(|dx|, |dy|) <= tan_half * (d - dz) / k_margin.
    const float lateral = std::fmax(half_extent.x, half_extent.y);
    float dist = half_extent.z + k_margin * lateral / tan_half;
    if (!(dist > half_extent.z) || !std::isfinite(dist)) dist = half_extent.z + 1.0f;  // a point or a sliver
    camera.look_at = center;
    camera.look_from = center + Vec3(0.0f, 0.0f, dist);
    camera.up = Vec3(0.0f, 1.0f, 0.0f);
    return camera;
}

Camera resolve_camera(const Scene& scene, const CameraOverrides& overrides)
{
    Camera camera = scene.camera ? *scene.camera : frame_camera(scene);
    if (overrides.look_from) camera.look_from = *overrides.look_from;
    if (overrides.look_at) camera.look_at = *overrides.look_at;
    if (overrides.up) camera.up = *overrides.up;
    if (overrides.fov) camera.vfov_degrees = *overrides.fov;

    if (!is_finite(camera.look_from) || !is_finite(camera.look_at) || !is_finite(camera.up))
        throw UsageError("camera: look-from, look-at and up must be finite");
    const Vec3 forward = camera.look_at - camera.look_from;
    if (!(length(forward) > 0.0f)) throw UsageError("camera: look-from and look-at are the same point");
    if (!(length(camera.up) > 0.0f)) throw UsageError("camera: the up vector is zero");
    const Vec3 side = cross(normalize(forward), normalize(camera.up));
    if (!(length(side) > 1e-6f)) throw UsageError("camera: the up vector is parallel to the view direction");
    if (!(camera.vfov_degrees > 0.0f && camera.vfov_degrees < 180.0f))
        throw UsageError("camera: field of view " + std::to_string(camera.vfov_degrees) + " degrees is outside (0, 180)");
    return camera;
}

}  // namespace gc
