#include "host/scene/camera_framing.h"

#include <cmath>
#include <string>

#include "host/util/error.h"

namespace gc {

namespace {

constexpr float k_default_fov_degrees = 40.0f;
constexpr float k_margin = 1.1f;

}  // namespace

Camera frame_camera(const Scene& scene)
{
    Camera camera;
    camera.vfov_degrees = k_default_fov_degrees;
    const Bounds3 b = scene.bounds();
    if (b.empty()) return camera;
    const Point3 center = b.centroid();
    float radius = 0.5f * length(b.diagonal());
    if (!(radius > 0.0f)) radius = 1.0f;  // a single point: any distance shows it
    // A sphere of radius r seen from distance d fills the half-angle asin(r/d).
    const float half = 0.5f * k_default_fov_degrees * 3.14159265f / 180.0f;
    const float dist = k_margin * radius / std::sin(half);
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
